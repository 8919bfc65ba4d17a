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

TEST_CASE("weighted percentile: equal weights are the nearest rank, weight moves it",
          "[statistics]") {
  std::vector<WeightedSample> v;
  for (int k = 20; k >= 1; --k) v.push_back({static_cast<float>(k), 1.0f});
  CHECK(weighted_percentile(v, 95.0) == 19.0);
  CHECK(weighted_percentile(v, 50.0) == 10.0);
  CHECK(weighted_percentile(v, 100.0) == 20.0);
  // One sample holding most of the weight is the percentile from 0 up to its share.
  std::vector<WeightedSample> w{{1.0f, 1.0f}, {2.0f, 96.0f}, {3.0f, 1.0f}, {4.0f, 2.0f}};
  CHECK(weighted_percentile(w, 0.0) == 1.0);
  CHECK(weighted_percentile(w, 50.0) == 2.0);
  CHECK(weighted_percentile(w, 97.0) == 2.0);
  CHECK(weighted_percentile(w, 98.0) == 3.0);
  CHECK(weighted_percentile(w, 99.0) == 4.0);
  // Zero weights never count; no weight at all is NaN.
  std::vector<WeightedSample> z{{5.0f, 0.0f}, {7.0f, 0.0f}};
  CHECK(std::isnan(weighted_percentile(z, 50.0)));
  std::vector<WeightedSample> m{{100.0f, 0.0f}, {7.0f, 1.0f}};
  CHECK(weighted_percentile(m, 100.0) == 7.0);
}

TEST_CASE("bootstrap interval of a mean: exact cases and its properties", "[statistics]") {
  // Two values {0, 10}: a resample's mean is 0, 5 or 10 with probabilities 1/4, 1/2, 1/4, so
  // the 2.5th and 97.5th percentiles of 10000 resampled means are 0 and 10.
  const std::vector<double> two{0.0, 10.0};
  const Interval i2 = bootstrap_mean_interval(two, 42);
  CHECK(i2.low == 0.0);
  CHECK(i2.high == 10.0);
  // One value, or all equal: the value itself.
  CHECK(bootstrap_mean_interval(std::vector<double>{3.5}, 1).low == 3.5);
  const Interval same = bootstrap_mean_interval(std::vector<double>{2, 2, 2, 2}, 7);
  CHECK(same.low == 2.0);
  CHECK(same.high == 2.0);
  CHECK(std::isnan(bootstrap_mean_interval(std::vector<double>{}, 1).low));
  // Five values: the interval holds the mean, lies within the range, and is reproducible.
  const std::vector<double> five{1, 2, 3, 4, 5};
  const Interval a = bootstrap_mean_interval(five, 99);
  CHECK(a.low < 3.0);
  CHECK(a.high > 3.0);
  CHECK(a.low >= 1.0);
  CHECK(a.high <= 5.0);
  // The normal approximation: mean +- 1.96 s / sqrt(n) with s = sqrt(2) (population sd) gives
  // [1.76, 4.24]; the percentile bootstrap of so few points lies near it.
  CHECK(a.low == Approx(1.76).margin(0.25));
  CHECK(a.high == Approx(4.24).margin(0.25));
  const Interval b = bootstrap_mean_interval(five, 99);
  CHECK(a.low == b.low);
  CHECK(a.high == b.high);
}
