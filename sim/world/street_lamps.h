#pragma once
// Street lamps along both sides of the road (SPEC 1b): point lights (inverse square, no
// occlusion) shining down in a cone, lighting the road and its verges; switched by the sun's
// elevation (a photocell) or by a schedule. Like the sun disc, the lamps themselves are not seen
// by captures: their light on surfaces is.
#include <cstddef>
#include <unordered_map>
#include <vector>

#include <glm/vec3.hpp>

#include "sim/colour/rgb.h"
#include "sim/world/lighting_params.h"

namespace ambisim {

class Spline3;

class StreetLamps {
 public:
  // road: the centre line at road-surface height; road_width_m: the asphalt width.
  StreetLamps(const LampParams& p, const Spline3& road, double road_width_m);

  // Irradiance (klx, RGB, the lamps at full power) on a surface at p with unit normal n.
  Rgb irradiance(const glm::dvec3& p, const glm::dvec3& n) const;
  // 0 (off) or 1 (on) at time t with the sun at elevation sun_elevation_deg.
  double level(double t, double sun_elevation_deg) const;

  const std::vector<glm::dvec3>& positions() const { return lamps_; }
  // Horizontal reach of a lamp's cone on flat ground (m).
  double reach_m() const { return reach_; }

 private:
  LampParams p_;
  std::vector<glm::dvec3> lamps_;
  double reach_ = 0.0;
  double cell_ = 32.0;  // bucket size
  std::unordered_map<long long, std::vector<std::size_t>> buckets_;
  double cos_full_ = 1.0, cos_edge_ = 0.0;  // full power inside, nothing outside the cone
  Rgb colour_intensity_{0.0f};
};

}  // namespace ambisim
