#include "sim/world/lighting_model.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

#include "sim/world/lighting.h"
#include "sim/world/solar_position.h"
#include "sim/world/world.h"

namespace ambisim {
namespace {

// Night sky: airglow and starlight, 0.002 lux on the ground (a moonless clear night), as a
// uniform radiance E / pi, in kcd/m^2.
constexpr float kNightRadiance = static_cast<float>(0.002e-3 / std::numbers::pi);
constexpr float kCloudAlbedo = 0.35f;  // grey cloud base seen from below

// Keyframed elevation/azimuth, linear between keys, constant outside.
void keyframe_sun(const std::vector<SunPathParams::Key>& k, double t, double* el, double* az) {
  if (t <= k.front().time_s || k.size() == 1) {
    *el = k.front().elevation_deg;
    *az = k.front().azimuth_deg;
    return;
  }
  if (t >= k.back().time_s) {
    *el = k.back().elevation_deg;
    *az = k.back().azimuth_deg;
    return;
  }
  std::size_t i = 1;
  while (k[i].time_s < t) ++i;
  const double u = (t - k[i - 1].time_s) / (k[i].time_s - k[i - 1].time_s);
  *el = k[i - 1].elevation_deg + u * (k[i].elevation_deg - k[i - 1].elevation_deg);
  *az = k[i - 1].azimuth_deg + u * (k[i].azimuth_deg - k[i - 1].azimuth_deg);
}

// SH9 of a radiance function over the upper hemisphere (zero below), by a midpoint rule in
// (cos theta, phi): equal solid angle per sample.
template <class F>
Sh9Rgb project_hemisphere(F radiance) {
  constexpr int kMu = 16, kPhi = 32;
  const double dw = (1.0 / kMu) * (2.0 * std::numbers::pi / kPhi);
  std::array<glm::dvec3, kShCount> acc{};
  for (int a = 0; a < kMu; ++a) {
    const double mu = (a + 0.5) / kMu, sn = std::sqrt(1.0 - mu * mu);
    for (int b = 0; b < kPhi; ++b) {
      const double ph = (b + 0.5) * 2.0 * std::numbers::pi / kPhi;
      const glm::dvec3 d(sn * std::cos(ph), sn * std::sin(ph), mu);
      const glm::dvec3 l(radiance(d));
      const ShBasis y = sh_basis(d);
      for (int k = 0; k < kShCount; ++k) acc[k] += l * (y[k] * dw);
    }
  }
  Sh9Rgb sh;
  for (int k = 0; k < kShCount; ++k) sh.c[k] = Rgb(acc[k]);
  return sh;
}

}  // namespace

Rgb LightingState::clear_sky(const glm::dvec3& d) const {
  if (sky_model == SkyParams::Model::gradient) {
    if (gradient.uniform) return gradient.uniform_radiance;
    const float t = static_cast<float>(std::sqrt(std::clamp(d.z, 0.0, 1.0)));
    return gradient.horizon + (gradient.zenith - gradient.horizon) * t;
  }
  return preetham->radiance(d) * static_cast<float>(sky_scale) + night_floor;
}

Rgb LightingState::sky(const glm::dvec3& o, const glm::dvec3& d) const {
  const Rgb clear = clear_sky(d);
  if (clouds == nullptr) return clear;
  const float c = static_cast<float>(clouds->opacity() * clouds->cover_along(o, d, time));
  return clear * (1.0f - c) + cloud_radiance * c;
}

Rgb LightingState::sky_irradiance(const glm::dvec3& n) const {
  const Rgb e = sh_irradiance(sky_sh, n);
  return Rgb(std::max(e.x, 0.0f), std::max(e.y, 0.0f), std::max(e.z, 0.0f));
}

LightingModel::LightingModel(const World& world) : p_(world.params().lighting()) {
  static_ = p_.is_static();
  legacy_ = p_.is_legacy();
  if (p_.clouds.enabled) {
    clouds_ = std::make_unique<CloudLayer>(p_.clouds, world.min_surface() + p_.clouds.altitude_m);
  }
  if (p_.lamps.enabled && !world.road().empty()) {
    lamps_ = std::make_unique<StreetLamps>(p_.lamps, world.road(), world.road_width_m());
  }
  if (p_.sun.path.type != SunPathParams::Type::fixed) {
    shadows_ = std::make_unique<SunShadows>(world, [this](double t) { return sun_at(t); });
  }
}

SunShadows::Sun LightingModel::sun_at(double t, double* apparent_elevation_deg) const {
  double el = p_.sun.elevation_deg, az = p_.sun.azimuth_deg;
  const SunPathParams& path = p_.sun.path;
  if (path.type == SunPathParams::Type::solar) {
    const double minutes = (path.start_s + t * path.time_scale) / 60.0;
    const SolarPosition s =
        noaa_solar_position(path.year, path.month, path.day, minutes, path.latitude_deg,
                            path.longitude_deg, path.utc_offset_h);
    el = s.apparent_elevation_deg;
    az = s.azimuth_deg;
  } else if (path.type == SunPathParams::Type::keyframes) {
    keyframe_sun(path.keys, t, &el, &az);
  }
  if (apparent_elevation_deg != nullptr) *apparent_elevation_deg = el;
  SunShadows::Sun sun;
  sun.dir = sun_direction(el, az);
  sun.on = p_.sun.enabled && el > 0.0;
  return sun;
}

LightingState LightingModel::compute(double t, bool set_shadows) {
  LightingState s;
  s.time = t;
  s.legacy = legacy_;
  double el = 0.0;
  const SunShadows::Sun sun = sun_at(t, &el);
  s.sun_dir = sun.dir;
  s.sun_elevation_deg = el;
  s.sky_model = p_.sky.model;
  s.gradient = p_.sky;

  if (p_.sky.model == SkyParams::Model::gradient) {
    s.sun_on = sun.on && p_.sun.radiance_ratio > 0.0;
    if (s.sun_on) {
      const Rgb ref = p_.sky.uniform ? p_.sky.uniform_radiance : p_.sky.zenith;
      const double l_sun = p_.sun.radiance_ratio * luminance(ref);
      s.e_sun = Rgb(static_cast<float>(l_sun * p_.sun.disc_solid_angle_sr)) * p_.sun.colour;
    }
  } else {
    s.preetham.emplace(p_.sky.turbidity, sun.dir);
    s.sky_scale = twilight_factor(el);
    s.night_floor = Rgb(el < 0.0 ? kNightRadiance : 0.0f);
    s.sun_on = sun.on;
    if (s.sun_on) s.e_sun = sun_irradiance(el, p_.sky.turbidity);
  }
  // The first model renders from the world's precomputed radiance: nothing else is needed
  // (planners' knowledge, info_at, asks for the rest).
  if (legacy_ && set_shadows) return s;
  // Clouds: their base lit by the sun and the clear sky.
  s.clouds = clouds_.get();
  const Sh9Rgb clear_sh = project_hemisphere([&](const glm::dvec3& d) { return s.clear_sky(d); });
  s.sky_sh = clear_sh;
  s.sky_irradiance_up = s.sky_irradiance({0.0, 0.0, 1.0});
  const Rgb ambient_up =
      s.sky_irradiance_up + s.e_sun * static_cast<float>(std::max(s.sun_dir.z, 0.0));
  if (s.clouds != nullptr) {
    s.cloud_radiance = ambient_up * static_cast<float>(kCloudAlbedo / std::numbers::pi);
    const float m = static_cast<float>(s.clouds->opacity() * s.clouds->mean_cover());
    s.sky_sh = project_hemisphere(
        [&](const glm::dvec3& d) { return s.clear_sky(d) * (1.0f - m) + s.cloud_radiance * m; });
    s.sky_irradiance_up = s.sky_irradiance({0.0, 0.0, 1.0});
  }
  s.lamps = lamps_.get();
  if (s.lamps != nullptr) s.lamp_level = s.lamps->level(t, el);
  s.fog = fog_at(p_.fog, t);
  s.fog_sky_distance_m = p_.fog.sky_distance_m;
  // The legacy fog colour is a radiance; in the lit models it is the fog's albedo, scattering
  // the sun and sky light isotropically.
  s.fog_inscatter = p_.sky.model == SkyParams::Model::gradient
                        ? p_.fog.colour
                        : p_.fog.colour * (s.e_sun + s.sky_irradiance_up) *
                              static_cast<float>(1.0 / (4.0 * std::numbers::pi));
  if (shadows_) {
    if (set_shadows) shadows_->set_time(t);
    s.shadows = shadows_.get();
  }
  return s;
}

const LightingState& LightingModel::state_at(double t) {
  if (!have_state_ || (state_.time != t && !static_)) {
    state_ = compute(t);
    have_state_ = true;
  }
  // Static light: one state for every time (only its clock moves).
  state_.time = t;
  return state_;
}

LightingModel::Scalars LightingModel::scalars_at(double t) const {
  Scalars sc;
  double el = 0.0;
  const SunShadows::Sun sun = sun_at(t, &el);
  sc.sun_dir = sun.dir;
  sc.sun_elevation_deg = el;
  if (p_.sky.model == SkyParams::Model::preetham) {
    const PreethamSky sky(p_.sky.turbidity, sun.dir);
    sc.sky_zenith = sky.zenith_luminance() * twilight_factor(el);
    if (sun.on) sc.sun = luminance(sun_irradiance(el, p_.sky.turbidity));
  } else {
    sc.sky_zenith = luminance(p_.sky.uniform ? p_.sky.uniform_radiance : p_.sky.zenith);
    if (sun.on) sc.sun = 1.0;
  }
  sc.fog_density = fog_at(p_.fog, t).density_per_m;
  sc.lamp_level = lamps_ ? lamps_->level(t, el) : 0.0;
  return sc;
}

LightingInfo LightingModel::info_at(double t) {
  if (have_info_ && info_time_ == t) return info_;
  // The state without touching the shadows (a planner may ask about any time while the frame's
  // state renders).
  const LightingState s = compute(t, false);
  LightingInfo info;
  info.sun_dir = s.sun_dir;
  info.sun_on = s.sun_on;
  info.sun_irradiance = s.e_sun;
  info.sky_sh = s.sky_sh;
  info.lamp_level = s.lamp_level;
  // Rates by central differences over +-0.5 s of the scalars that set the light's level.
  const double h = 0.5, t0 = std::max(t - h, 0.0), t1 = t + h, span = t1 - t0;
  const Scalars a = scalars_at(t0), b = scalars_at(t1);
  const auto rel = [&](double x0, double x1) {
    const double m = 0.5 * (std::abs(x0) + std::abs(x1));
    return m > 1e-12 ? std::abs(x1 - x0) / (m * span) : 0.0;
  };
  // The illuminance on a horizontal surface and on a vertical one facing the sun (a uniform sky
  // of the zenith's luminance plus the sun): the relative rate of the total a surface receives,
  // not of the sun alone, which near the horizon dims fast while the sky still lights the
  // scene (the sun's own rate overstated the change of probes at 4 deg elevation by 7x).
  const auto horizontal = [](const Scalars& x) {
    return std::numbers::pi * x.sky_zenith + x.sun * std::max(x.sun_dir.z, 0.0);
  };
  const auto facing_sun = [](const Scalars& x) {
    const double cos_el = std::sqrt(std::max(0.0, 1.0 - x.sun_dir.z * x.sun_dir.z));
    return 0.5 * std::numbers::pi * x.sky_zenith + x.sun * (x.sun_dir.z > 0.0 ? cos_el : 0.0);
  };
  double rate = std::max(rel(horizontal(a), horizontal(b)), rel(facing_sun(a), facing_sun(b)));
  rate = std::max(rate, std::acos(std::clamp(glm::dot(a.sun_dir, b.sun_dir), -1.0, 1.0)) / span);
  rate = std::max(rate, rel(a.fog_density, b.fog_density));
  info.sun_sky_change_rate = rate;
  info.lamp_change_rate = a.lamp_level != b.lamp_level ? 1.0 / span : 0.0;
  info.change_rate = std::max(info.sun_sky_change_rate, info.lamp_change_rate);
  info_ = info;
  info_time_ = t;
  have_info_ = true;
  return info;
}

double LightingModel::local_change_rate(const glm::dvec3& p, double t) {
  const LightingInfo info = info_at(t);
  double rate = info.sun_sky_change_rate;
  if (clouds_ && info.sun_on) rate = std::max(rate, clouds_->change_rate(p, info.sun_dir, t));
  return rate;
}

}  // namespace ambisim
