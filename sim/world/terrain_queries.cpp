#include "sim/world/terrain_queries.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace ambisim {

glm::dvec3 right_of(const glm::dvec3& forward) {
  const glm::dvec3 r(forward.y, -forward.x, 0.0);  // forward x up, with up = +z
  const double len = glm::length(r);
  return len > 1e-12 ? r / len : glm::dvec3(1.0, 0.0, 0.0);
}

glm::dvec3 lane_point(const Spline3& road, double s, int direction, double offset, double height) {
  s = std::clamp(s, 0.0, road.length());
  const glm::dvec3 forward = static_cast<double>(direction) * road.tangent(s);
  return road.at(s) + offset * right_of(forward) + glm::dvec3(0.0, 0.0, height);
}

glm::dvec3 lane_derivative(const Spline3& road, double s, int direction, double offset) {
  const double h = std::min(0.5, 0.5 * road.length());
  const double a = std::clamp(s - h, 0.0, road.length());
  const double b = std::clamp(s + h, 0.0, road.length());
  if (b <= a) return road.tangent(s);
  return (lane_point(road, b, direction, offset, 0.0) -
          lane_point(road, a, direction, offset, 0.0)) /
         (b - a);
}

}  // namespace ambisim
