// Metrics statistics: nearest-rank percentiles against hand-computed ranks, running and
// time-weighted means.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "sim/base/statistics.h"

using namespace ambisim;

TEST_CASE("nearest-rank percentile of 1..20", "[metrics]") {
  std::vector<double> v;
  for (int k = 20; k >= 1; --k) v.push_back(k);  // reversed: the helper must not assume order
  // rank = ceil(p n / 100): p95 -> 19, p50 -> 10, p5 -> 1, p0 -> the minimum, p100 -> 20.
  CHECK(percentile_nearest_rank(v, 95.0) == 19.0);
  CHECK(percentile_nearest_rank(v, 50.0) == 10.0);
  CHECK(percentile_nearest_rank(v, 5.0) == 1.0);
  CHECK(percentile_nearest_rank(v, 0.0) == 1.0);
  CHECK(percentile_nearest_rank(v, 100.0) == 20.0);
  CHECK(percentile_nearest_rank(v, 95.1) == 20.0);   // 19.02 rounds up to rank 20
  CHECK(percentile_nearest_rank(v, 150.0) == 20.0);  // clamped
}

TEST_CASE("nearest-rank percentile of the textbook five values", "[metrics]") {
  // The worked example of the nearest-rank method: {15, 20, 35, 40, 50}.
  const std::vector<double> v{40, 15, 50, 35, 20};
  CHECK(percentile_nearest_rank(v, 5.0) == 15.0);
  CHECK(percentile_nearest_rank(v, 30.0) == 20.0);
  CHECK(percentile_nearest_rank(v, 40.0) == 20.0);
  CHECK(percentile_nearest_rank(v, 50.0) == 35.0);
  CHECK(percentile_nearest_rank(v, 100.0) == 50.0);
  const std::vector<float> f{40.f, 15.f, 50.f, 35.f, 20.f};
  CHECK(percentile_nearest_rank(f, 50.0) == 35.0);
  CHECK(nearest_rank_index(5, 0.0) == 0);
  CHECK(nearest_rank_index(1, 95.0) == 0);
}

TEST_CASE("percentile and mean of no samples are NaN", "[metrics]") {
  CHECK(std::isnan(percentile_nearest_rank(std::vector<double>{}, 95.0)));
  CHECK(std::isnan(mean_of(std::vector<double>{})));
  RunningStats s;
  CHECK(std::isnan(s.mean()));
  CHECK(std::isnan(s.max()));
  TimeWeightedMean t;
  CHECK(std::isnan(t.mean()));
}

TEST_CASE("running and time-weighted means", "[metrics]") {
  constexpr double kTol = 1e-15;
  RunningStats s;
  for (double x : {2.0, -1.0, 5.0, 2.0}) s.add(x);
  CHECK(s.count() == 4);
  CHECK(s.mean() == Approx(2.0).margin(kTol));
  CHECK(s.max() == 5.0);
  CHECK(s.min() == -1.0);
  CHECK(mean_of(std::vector<double>{1, 2, 3, 4}) == Approx(2.5).margin(kTol));
  // 0.25 for 0.01 s, then 1.0 for 0.1 s.
  TimeWeightedMean t;
  t.add(0.25, 0.01);
  t.add(1.0, 0.1);
  CHECK(t.mean() == Approx((0.25 * 0.01 + 0.1) / 0.11).margin(kTol));
  CHECK(t.weight() == Approx(0.11).margin(kTol));
}
