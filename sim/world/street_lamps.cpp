#include "sim/world/street_lamps.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

#include "sim/world/spline.h"

namespace ambisim {
namespace {

long long bucket_key(long long i, long long j) { return (i << 32) ^ (j & 0xffffffffLL); }

}  // namespace

StreetLamps::StreetLamps(const LampParams& p, const Spline3& road, double road_width_m) : p_(p) {
  const double offset = p.offset_m >= 0.0 ? p.offset_m : 0.5 * road_width_m + 1.0;
  if (!road.empty() && p.spacing_m > 0.0) {
    for (double s = 0.5 * p.spacing_m; s < road.length(); s += p.spacing_m) {
      const glm::dvec3 c = road.at(s), t = road.tangent(s);
      const glm::dvec3 side = glm::normalize(glm::dvec3(-t.y, t.x, 0.0));
      for (int k : {-1, 1})
        lamps_.push_back(c + side * (k * offset) + glm::dvec3(0, 0, p.height_m));
    }
  }
  const double cone = p.cone_deg * std::numbers::pi / 180.0;
  const double full = std::max(0.0, p.cone_deg - 10.0) * std::numbers::pi / 180.0;
  cos_edge_ = std::cos(cone);
  cos_full_ = std::cos(full);
  reach_ = p.height_m * std::tan(std::min(cone, 89.0 * std::numbers::pi / 180.0));
  cell_ = std::max(8.0, reach_);
  for (std::size_t k = 0; k < lamps_.size(); ++k) {
    const long long i = static_cast<long long>(std::floor(lamps_[k].x / cell_));
    const long long j = static_cast<long long>(std::floor(lamps_[k].y / cell_));
    buckets_[bucket_key(i, j)].push_back(k);
  }
  colour_intensity_ = p.colour * static_cast<float>(p.intensity_kcd);
}

Rgb StreetLamps::irradiance(const glm::dvec3& p, const glm::dvec3& n) const {
  if (lamps_.empty() || p_.intensity_kcd <= 0.0) return Rgb(0.0f);
  const long long i = static_cast<long long>(std::floor(p.x / cell_));
  const long long j = static_cast<long long>(std::floor(p.y / cell_));
  double e = 0.0;
  for (long long di = -1; di <= 1; ++di) {
    for (long long dj = -1; dj <= 1; ++dj) {
      const auto it = buckets_.find(bucket_key(i + di, j + dj));
      if (it == buckets_.end()) continue;
      for (std::size_t k : it->second) {
        const glm::dvec3 v = lamps_[k] - p;  // toward the lamp
        const double d2 = glm::dot(v, v);
        if (d2 < 1e-4) continue;
        const double d = std::sqrt(d2);
        const double cos_axis = v.z / d;  // the angle from the lamp's downward axis
        if (cos_axis <= cos_edge_) continue;
        const double cone =
            cos_axis >= cos_full_
                ? 1.0
                : (cos_axis - cos_edge_) / (cos_full_ - cos_edge_);  // linear soft edge
        const double facing = glm::dot(n, v) / d;
        if (facing <= 0.0) continue;
        e += cone * facing / d2;
      }
    }
  }
  return colour_intensity_ * static_cast<float>(e);
}

double StreetLamps::level(double t, double sun_elevation_deg) const {
  if (p_.schedule.empty()) return sun_elevation_deg < p_.on_below_elevation_deg ? 1.0 : 0.0;
  bool on = false;  // before the first switch: off
  for (const auto& s : p_.schedule) {
    if (s.time_s <= t) on = s.on;
  }
  return on ? 1.0 : 0.0;
}

}  // namespace ambisim
