// Spline3: passes through its control points, arc length matches closed forms.
#include <catch2/catch.hpp>
#include <cmath>

#include <glm/geometric.hpp>

#include "sim/world/spline.h"

using ambisim::Spline3;

TEST_CASE("spline through collinear points is the straight segment", "[spline]") {
  const Spline3 s({{0, 0, 0}, {10, 0, 0}, {30, 0, 0}});
  // Arc length of a straight line is exact up to the table's float sums.
  CHECK(s.length() == Approx(30.0).epsilon(1e-9));
  // at() interpolates the arc-length table linearly: 64 samples per segment give a position
  // error of 1.7e-4 m here, where the speed along the curve varies within a segment.
  CHECK(s.at(12.5).x == Approx(12.5).margin(1e-3));
  CHECK(s.at(12.5).y == Approx(0.0).margin(1e-12));
  CHECK(s.tangent(5.0).x == Approx(1.0).epsilon(1e-9));
  CHECK(s.closest_s({17.0, 4.0, 0.0}) == Approx(17.0).epsilon(1e-6));
  CHECK(s.at(-5.0).x == Approx(0.0).margin(1e-12));  // clamped
}

TEST_CASE("spline interpolates control points and approximates a circle", "[spline]") {
  std::vector<glm::dvec3> pts;
  const double r = 100.0;
  for (int k = 0; k <= 24; ++k) {
    const double a = 2.0 * M_PI * k / 24.0;
    pts.push_back({r * std::cos(a), r * std::sin(a), 0.0});
  }
  const Spline3 s(pts);
  // Centripetal Catmull-Rom through 24 points on a circle: length within 0.1% of 2 pi r
  // (measured 0.004%), and away from the two end segments (whose phantom end points are
  // mirrored, not wrapped) the curve stays within 0.1 m of the circle.
  CHECK(s.length() == Approx(2.0 * M_PI * r).epsilon(1e-3));
  const double seg = s.length() / 24.0;
  for (double x = seg; x < s.length() - seg; x += 7.3) {
    CHECK(std::abs(glm::length(s.at(x)) - r) < 0.1);
  }
  // Control point k sits at arc length ~ k/24 of the circumference.
  const double s6 = s.closest_s(pts[6]);
  CHECK(glm::length(s.at(s6) - pts[6]) < 1e-6);
}
