// Accuracy metrics: relative error closed forms, CIEDE2000 of the displayed colours, the
// reference exposure and the normal sets.
#include <catch2/catch.hpp>
#include <cmath>
#include <set>
#include <tuple>
#include <vector>

#include <glm/geometric.hpp>

#include "sim/colour/tone_map.h"
#include "sim/metrics/accuracy.h"

using namespace ambisim;

namespace {
constexpr double kRelTol = 1e-7;  // float inputs, double arithmetic
constexpr double kExposureTol = 1e-12;
constexpr double kUnitTol = 1e-15;
}  // namespace

TEST_CASE("relative error closed forms", "[metrics]") {
  const Rgb r(0.2f, 0.5f, 1.5f);
  CHECK(relative_error(r, r, 1e-6) == 0.0);
  CHECK(relative_error(2.0f * r, r, 1e-6) == Approx(1.0).margin(kRelTol));
  CHECK(relative_error(Rgb(0.0f), r, 1e-6) == Approx(1.0).margin(kRelTol));
  // 3-4-5 triangle: |(0.3, 0.4, 0)| = 0.5 against |R| = 1.
  CHECK(relative_error(Rgb(1.3f, 0.4f, 0.0f), Rgb(1.0f, 0.0f, 0.0f), 1e-6) ==
        Approx(0.5).margin(kRelTol));
  // A black reference: the floor is the denominator.
  CHECK(relative_error(Rgb(3e-6f, 4e-6f, 0.0f), Rgb(0.0f), 1e-6) == Approx(5.0).margin(1e-5));
  // Symmetric in the sign of the error.
  CHECK(relative_error(r + Rgb(0.1f, 0, 0), r, 1e-6) ==
        Approx(relative_error(r - Rgb(0.1f, 0, 0), r, 1e-6)).margin(kRelTol));
}

TEST_CASE("display difference of identical colours is 0 and grows with the error", "[metrics]") {
  const Rgb r(0.3f, 0.6f, 0.2f);
  CHECK(display_difference(r, r, 1.0) == 0.0);
  CHECK(display_difference(display_lab(r, 2.0), display_lab(r, 2.0)) == 0.0);
  const double small = display_difference(1.05f * r, r, 1.0);
  const double large = display_difference(1.5f * r, r, 1.0);
  CHECK(small > 0.0);
  CHECK(large > small);
  // The Lab overload is the same number.
  CHECK(display_difference(display_lab(1.5f * r, 1.0), display_lab(r, 1.0)) == large);
}

TEST_CASE("reference exposure is key over the log-average luminance", "[metrics]") {
  // Greys (v, v, v) have luminance v, so log-average = delta + v with delta = 1e-4.
  const std::vector<Rgb> grey(10, Rgb(2.0f));
  CHECK(reference_exposure(grey, 0.18) == Approx(0.18 / (2.0 + 1e-4)).epsilon(kExposureTol));
  // Geometric mean of two greys: sqrt((a + d)(b + d)).
  const std::vector<Rgb> two{Rgb(1.0f), Rgb(4.0f)};
  CHECK(reference_exposure(two, 0.18) ==
        Approx(0.18 / std::sqrt((1.0 + 1e-4) * (4.0 + 1e-4))).epsilon(kExposureTol));
  // No reference at all still gives a finite exposure.
  CHECK(std::isfinite(reference_exposure({}, 0.18)));
}

TEST_CASE("normal sets", "[metrics]") {
  const auto six = normal_set("axes6");
  const auto all = normal_set("axes26");
  CHECK(six.size() == 6);
  CHECK(all.size() == 26);
  std::set<std::tuple<double, double, double>> distinct;
  glm::dvec3 sum(0.0);
  for (const auto& n : all) {
    CHECK(glm::length(n) == Approx(1.0).margin(kUnitTol));
    distinct.insert({n.x, n.y, n.z});
    sum += n;
  }
  CHECK(distinct.size() == 26);
  // Symmetric under n -> -n: the directions sum to 0.
  CHECK(glm::length(sum) < 1e-12);
  for (const auto& n : six) CHECK(distinct.count({n.x, n.y, n.z}) == 1);
  CHECK_THROWS_AS(normal_set("axes7"), std::invalid_argument);
}
