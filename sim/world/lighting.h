#pragma once
// Sun, sky and fog in linear HDR (SPEC section 1). Units: the sky's zenith radiance is O(1);
// the sun is a disc of radiance `radiance_ratio` x the zenith luminance, seen only through
// the direct term E_sun (captures exclude the disc).
//
// Sky irradiance E_sky(n) ignores terrain occlusion of the sky and has no ground bounce (one
// bounce only): it integrates the sky over the upper hemisphere, so it depends only on n.z.
#include <array>

#include <glm/vec3.hpp>

#include "sim/colour/rgb.h"
#include "sim/world/world_params.h"

namespace ambisim {

// Unit direction toward the sun: compass azimuth (0 = north = +y, 90 = east = +x).
glm::dvec3 sun_direction(double elevation_deg, double azimuth_deg);

class Lighting {
 public:
  Lighting() = default;
  Lighting(const SunParams& sun, const SkyParams& sky, const FogParams& fog);

  const glm::dvec3& sun_dir() const { return sun_dir_; }
  // Irradiance on a plane facing the sun (0 when the sun is off or below the horizon).
  const Rgb& sun_irradiance() const { return e_sun_; }
  bool sun_on() const { return sun_on_; }

  // Sky radiance toward unit direction d (below the horizon: the horizon colour).
  Rgb sky_radiance(const glm::dvec3& d) const;
  // Sky irradiance on a surface with unit normal of height component nz in [-1, 1]
  // (uniform sky: pi S (1 + nz) / 2 exactly; gradient sky: tabulated, linear in nz).
  Rgb sky_irradiance(double nz) const;

  // Lambertian one-bounce radiance of a surface point: albedo/pi (E_sun max(0, n.s) vis + E_sky).
  Rgb surface_radiance(const Rgb& albedo, const glm::dvec3& n, bool sunlit) const;

  // Homogeneous fog over a path of length t: L T + L_fog (1 - T), T = exp(-sigma t).
  Rgb apply_fog(const Rgb& l, double t) const;
  // What an escaping (sky) ray returns: the sky fogged over fog.sky_distance_m.
  Rgb sky_ray(const glm::dvec3& d) const;

  static constexpr int kSkyTable = 257;

 private:
  SkyParams sky_;
  FogParams fog_;
  glm::dvec3 sun_dir_{0.0, 0.0, 1.0};
  Rgb e_sun_{0.0f};
  bool sun_on_ = false;
  std::array<Rgb, kSkyTable> e_sky_{};  // at nz = -1 + 2 k / (kSkyTable - 1)
};

}  // namespace ambisim
