#include "sim/world/lighting.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

namespace ambisim {

glm::dvec3 sun_direction(double elevation_deg, double azimuth_deg) {
  const double e = elevation_deg * std::numbers::pi / 180.0,
               a = azimuth_deg * std::numbers::pi / 180.0;
  return {std::sin(a) * std::cos(e), std::cos(a) * std::cos(e), std::sin(e)};
}

Lighting::Lighting(const SunParams& sun, const SkyParams& sky, const FogParams& fog)
    : sky_(sky), fog_(fog) {
  sun_dir_ = sun_direction(sun.elevation_deg, sun.azimuth_deg);
  sun_on_ = sun.enabled && sun.elevation_deg > 0.0 && sun.radiance_ratio > 0.0;
  if (sun_on_) {
    const Rgb ref = sky.uniform ? sky.uniform_radiance : sky.zenith;
    const double l_sun = sun.radiance_ratio * luminance(ref);
    e_sun_ = Rgb(static_cast<float>(l_sun * sun.disc_solid_angle_sr)) * sun.colour;
  }
  // Tabulate E_sky(nz): the sky is symmetric about z, so integrate once per nz with a
  // midpoint rule over (mu = cos zenith angle, azimuth) of the upper hemisphere, where
  // dOmega = dmu dphi; 64 x 96 cells (measured error in test_world.cpp).
  constexpr int kMu = 64, kPhi = 96;
  for (int k = 0; k < kSkyTable; ++k) {
    const double nz = -1.0 + 2.0 * k / (kSkyTable - 1);
    const glm::dvec3 n{std::sqrt(std::max(0.0, 1.0 - nz * nz)), 0.0, nz};
    if (sky.uniform) {
      e_sky_[k] =
          Rgb(static_cast<float>(std::numbers::pi * (1.0 + nz) / 2.0)) * sky.uniform_radiance;
      continue;
    }
    glm::dvec3 sum(0.0);
    const double dw = (1.0 / kMu) * (2.0 * std::numbers::pi / kPhi);
    for (int a = 0; a < kMu; ++a) {
      const double mu = (a + 0.5) / kMu, sn = std::sqrt(1.0 - mu * mu);
      const glm::dvec3 l(sky_radiance({sn, 0.0, mu}));
      for (int b = 0; b < kPhi; ++b) {
        const double ph = (b + 0.5) * 2.0 * std::numbers::pi / kPhi;
        const double c = n.x * sn * std::cos(ph) + n.z * mu;
        if (c > 0.0) sum += l * (c * dw);
      }
    }
    e_sky_[k] = Rgb(sum);
  }
}

Rgb Lighting::sky_radiance(const glm::dvec3& d) const {
  if (sky_.uniform) return sky_.uniform_radiance;
  // sqrt of the elevation sine: a bright band near the horizon that fades quickly upward.
  const float t = static_cast<float>(std::sqrt(std::clamp(d.z, 0.0, 1.0)));
  return sky_.horizon + (sky_.zenith - sky_.horizon) * t;
}

Rgb Lighting::sky_irradiance(double nz) const {
  const double x = (std::clamp(nz, -1.0, 1.0) + 1.0) * 0.5 * (kSkyTable - 1);
  const int k = std::min(static_cast<int>(x), kSkyTable - 2);
  const float f = static_cast<float>(x - k);
  return e_sky_[k] + (e_sky_[k + 1] - e_sky_[k]) * f;
}

Rgb Lighting::surface_radiance(const Rgb& albedo, const glm::dvec3& n, bool sunlit) const {
  Rgb e = sky_irradiance(n.z);
  if (sunlit && sun_on_) {
    const double c = glm::dot(n, sun_dir_);
    if (c > 0.0) e += e_sun_ * static_cast<float>(c);
  }
  return albedo * e * static_cast<float>(1.0 / std::numbers::pi);
}

Rgb Lighting::apply_fog(const Rgb& l, double t) const {
  if (fog_.extinction_per_m <= 0.0) return l;
  const float tr = static_cast<float>(std::exp(-fog_.extinction_per_m * t));
  return l * tr + fog_.colour * (1.0f - tr);
}

Rgb Lighting::sky_ray(const glm::dvec3& d) const {
  return apply_fog(sky_radiance(d), fog_.sky_distance_m);
}

}  // namespace ambisim
