// Spline3: passes through its control points, arc length matches closed forms.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <vector>

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

namespace {

// Every closest_s() answer against the coarse scan's, bit for bit (the tree search only skips
// samples that are provably farther, and breaks ties toward the lower index as the scan does).
int count_differences(const Spline3& s, const std::vector<glm::dvec3>& points) {
  int differ = 0;
  for (const auto& p : points) differ += s.closest_s(p) != s.closest_s_reference(p) ? 1 : 0;
  return differ;
}

}  // namespace

TEST_CASE("closest_s's tree search equals the coarse scan on winding, looping and long curves",
          "[spline]") {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  // A 6 km random-walk road (the shape of the generated motorways), a closed circle whose ends
  // meet (equal distances at the seam), and a hairpin that doubles back on itself 5 m apart.
  std::vector<glm::dvec3> walk{{0.0, 0.0, 0.0}};
  double heading = 0.0;
  for (int k = 0; k < 120; ++k) {
    heading += 0.4 * unit(rng);
    walk.push_back(walk.back() +
                   50.0 * glm::dvec3(std::cos(heading), std::sin(heading), 0.1 * unit(rng)));
  }
  std::vector<glm::dvec3> circle;
  for (int k = 0; k <= 32; ++k) {
    const double a = 2.0 * M_PI * k / 32.0;
    circle.push_back({300.0 * std::cos(a), 300.0 * std::sin(a), 0.0});
  }
  std::vector<glm::dvec3> hairpin{{0, 0, 0}, {400, 0, 0}, {405, 2.5, 0}, {400, 5, 0}, {0, 5, 0}};
  for (const std::vector<glm::dvec3>* points : {&walk, &circle, &hairpin}) {
    const Spline3 s(*points);
    std::uniform_real_distribution<double> along(0.0, s.length());
    std::vector<glm::dvec3> queries;
    for (int i = 0; i < 4000; ++i) {
      const glm::dvec3 on = s.at(along(rng));
      queries.push_back(on + 15.0 * glm::dvec3(unit(rng), unit(rng), 0.2 * unit(rng)));  // near
      queries.push_back(on + 2000.0 * glm::dvec3(unit(rng), unit(rng), unit(rng)));      // far
    }
    // Points exactly on the table's samples (distance 0) and the circle's centre (all equal).
    for (double x = 0.0; x <= s.length(); x += s.length() / 97.0) queries.push_back(s.at(x));
    queries.push_back({0.0, 0.0, 0.0});
    queries.push_back({1e7, -1e7, 3e3});
    CHECK(count_differences(s, queries) == 0);
  }
}

TEST_CASE("first_sample_after's buckets equal the binary search, on and between the samples",
          "[spline]") {
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  // Segments from 2 m to 200 m long, so a bucket (a sample's average arc length) holds from
  // none to many samples.
  std::vector<glm::dvec3> points{{0.0, 0.0, 0.0}};
  for (int k = 0; k < 60; ++k) {
    const double len = k % 3 == 0 ? 2.0 : 100.0 + 100.0 * unit(rng);
    points.push_back(points.back() + len * glm::dvec3(1.0, 0.3 * unit(rng), 0.05 * unit(rng)));
  }
  const Spline3 s(points);
  std::vector<double> queries{0.0, s.length()};
  for (const double x : s.sample_arc_lengths()) {
    queries.push_back(x);  // exactly on a sample: the first sample beyond it is the next one
    queries.push_back(std::nextafter(x, -1.0));
    queries.push_back(std::nextafter(x, 1e9));
  }
  std::uniform_real_distribution<double> along(0.0, s.length());
  for (int i = 0; i < 20000; ++i) queries.push_back(along(rng));
  std::size_t differences = 0;
  for (const double x : queries) {
    if (x < 0.0 || x > s.length()) continue;  // first_sample_after's range
    differences += s.first_sample_after(x) != s.first_sample_after_reference(x) ? 1 : 0;
  }
  CHECK(differences == 0);
  CHECK(queries.size() > 20000 + 3 * 60 * 64);
}
