// Coverage: the required-spacing rule and the demand point generator.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "sim/metrics/coverage.h"

using namespace ambisim;

namespace {
constexpr double kPosTol = 1e-9;  // m

LookupResult lookup(double spacing, bool fell_back = false, int contributors = 1) {
  LookupResult r;
  r.spacing_m = spacing;
  r.fell_back = fell_back;
  r.contributor_count = contributors;
  return r;
}

double ground(double x, double y) { return 10.0 + 0.1 * x - 0.05 * y; }
}  // namespace

TEST_CASE("required spacing is max(s_min, alpha d)", "[metrics]") {
  const CoverageRule rule;  // 4 m, 0.25
  CHECK(required_spacing(0.0, rule) == 4.0);
  CHECK(required_spacing(16.0, rule) == 4.0);  // the knee
  CHECK(required_spacing(100.0, rule) == 25.0);
  CHECK(required_spacing(100.0, CoverageRule{2.0, 0.0}) == 2.0);
}

TEST_CASE("a demand point is served only by a close enough probe without fallback", "[metrics]") {
  const CoverageRule rule;
  CHECK(is_served(lookup(0.0), 0.0, rule));  // exact (oracle)
  CHECK(is_served(lookup(4.0), 1.0, rule));  // at the floor
  CHECK_FALSE(is_served(lookup(4.5), 1.0, rule));
  CHECK(is_served(lookup(25.0), 100.0, rule));  // exactly the requirement
  CHECK_FALSE(is_served(lookup(25.01), 100.0, rule));
  CHECK_FALSE(is_served(lookup(1.0, true), 100.0, rule));      // fell back
  CHECK_FALSE(is_served(lookup(1.0, false, 0), 100.0, rule));  // names no probe
  CHECK_FALSE(is_served(lookup(std::numeric_limits<double>::infinity()), 1e9, rule));
  CHECK_FALSE(is_served(lookup(std::nan("")), 100.0, rule));
}

TEST_CASE("demand points: counts, layout and determinism", "[metrics]") {
  const DemandLayout layout;  // 6 rings x 8 azimuths + 4 ahead
  const glm::dvec3 cam(100.0, -50.0, 40.0);
  const glm::dvec3 vel(0.0, 30.0, 2.0);  // heading +y
  const auto pts = demand_points(cam, vel, ground, layout);
  REQUIRE(pts.size() == 6 * 8 + 4);
  CHECK(pts == demand_points(cam, vel, ground, layout));

  for (std::size_t k = 0; k < pts.size(); ++k) {
    const auto& p = pts[k];
    CHECK(p.position.z == Approx(ground(p.position.x, p.position.y) + 1.5).margin(kPosTol));
    CHECK(p.distance_m == Approx(glm::length(p.position - cam)).margin(kPosTol));
    if (k < 48) {
      CHECK(p.kind == DemandKind::ring);
      const double r = layout.ring_radii_m[k / 8];
      const glm::dvec2 h(p.position.x - cam.x, p.position.y - cam.y);
      CHECK(glm::length(h) == Approx(r).margin(kPosTol));
      // Azimuth k % 8 steps of 45 degrees counter-clockwise from the heading (+y).
      const double a = std::atan2(1.0, 0.0) + (k % 8) * std::atan(1.0);
      CHECK(h.x == Approx(r * std::cos(a)).margin(kPosTol));
      CHECK(h.y == Approx(r * std::sin(a)).margin(kPosTol));
    } else {
      CHECK(p.kind == DemandKind::ahead);
      const double t = layout.ahead_s[k - 48];
      CHECK(p.position.x == Approx(cam.x).margin(kPosTol));
      CHECK(p.position.y == Approx(cam.y + 30.0 * t).margin(kPosTol));
    }
  }
}

TEST_CASE("demand points of a static camera face +x and keep their count", "[metrics]") {
  DemandLayout layout;
  layout.ring_radii_m = {5.0};
  layout.azimuths = 4;
  layout.ahead_s = {1.0, 2.0};
  const glm::dvec3 cam(0.0, 0.0, 3.0);
  const auto pts = demand_points(cam, glm::dvec3(0.0, 0.0, -1.0), ground, layout);
  REQUIRE(pts.size() == 6);
  CHECK(pts[0].position.x == Approx(5.0).margin(kPosTol));
  CHECK(pts[0].position.y == Approx(0.0).margin(kPosTol));
  CHECK(pts[1].position.y == Approx(5.0).margin(kPosTol));
  CHECK(pts[4].position.x == Approx(0.0).margin(kPosTol));  // ahead of a static camera: below it
  CHECK(pts[5].position.y == Approx(0.0).margin(kPosTol));
  CHECK(std::string(demand_kind_name(pts[5].kind)) == "ahead");
}
