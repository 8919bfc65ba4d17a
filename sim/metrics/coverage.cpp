#include "sim/metrics/coverage.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

namespace ambisim {
namespace {

// Below this horizontal speed (m/s) the heading is undefined; fall back to +x.
constexpr double kMinHeadingSpeed = 1e-6;

glm::dvec3 on_ground(double x, double y, const std::function<double(double, double)>& ground,
                     double height) {
  return {x, y, ground(x, y) + height};
}

}  // namespace

double required_spacing(double distance_m, const CoverageRule& rule) {
  return std::max(rule.min_spacing_m, rule.spacing_per_m * distance_m);
}

bool is_served(const LookupResult& lookup, double distance_m, const CoverageRule& rule) {
  // Written so a NaN spacing compares false and is unserved.
  return !lookup.fell_back && lookup.contributor_count > 0 &&
         lookup.spacing_m <= required_spacing(distance_m, rule);
}

const char* demand_kind_name(DemandKind kind) {
  switch (kind) {
    case DemandKind::receiver:
      return "receiver";
    case DemandKind::ring:
      return "ring";
    case DemandKind::ahead:
      return "ahead";
  }
  return "?";
}

std::vector<DemandPoint> demand_points(const glm::dvec3& camera_position,
                                       const glm::dvec3& camera_velocity,
                                       const std::function<double(double, double)>& ground_height,
                                       const DemandLayout& layout) {
  const glm::dvec2 v(camera_velocity.x, camera_velocity.y);
  const double speed = glm::length(v);
  const double heading = speed > kMinHeadingSpeed ? std::atan2(v.y, v.x) : 0.0;

  std::vector<DemandPoint> out;
  out.reserve(layout.ring_radii_m.size() * static_cast<std::size_t>(layout.azimuths) +
              layout.ahead_s.size());
  const auto push = [&](double x, double y, DemandKind kind) {
    const glm::dvec3 p = on_ground(x, y, ground_height, layout.height_m);
    out.push_back({p, glm::length(p - camera_position), kind});
  };
  for (double r : layout.ring_radii_m) {
    for (int k = 0; k < layout.azimuths; ++k) {
      const double a = heading + 2.0 * std::numbers::pi * k / layout.azimuths;
      push(camera_position.x + r * std::cos(a), camera_position.y + r * std::sin(a),
           DemandKind::ring);
    }
  }
  for (double t : layout.ahead_s) {
    push(camera_position.x + v.x * t, camera_position.y + v.y * t, DemandKind::ahead);
  }
  return out;
}

}  // namespace ambisim
