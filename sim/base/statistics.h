#pragma once
// Summary statistics for the metrics: a running mean/max, a time-weighted mean, and exact
// percentiles. Everything is order-deterministic: the same samples added in the same order give
// bit-identical results (plain double sums, no parallel reduction).
#include <cstdint>
#include <span>

namespace ambisim {

// Count, sum, min and max of a stream of finite values. mean() is NaN when empty (so "no data"
// never reads as a perfect 0); max()/min() likewise.
class RunningStats {
 public:
  void add(double x);
  std::int64_t count() const { return count_; }
  double sum() const { return sum_; }
  double mean() const;
  double max() const;
  double min() const;

 private:
  std::int64_t count_ = 0;
  double sum_ = 0.0;
  double max_ = 0.0;
  double min_ = 0.0;
};

// Mean of a piecewise-constant signal: sum(w x) / sum(w) with weights w >= 0 (frame dt), so a
// 10 fps stretch counts ten times as much per frame as a 100 fps one. NaN when no weight.
class TimeWeightedMean {
 public:
  void add(double x, double weight);
  double mean() const;
  double weight() const { return weight_; }

 private:
  double weighted_sum_ = 0.0;
  double weight_ = 0.0;
};

// Nearest-rank percentile (the definition of NIST/Wikipedia "nearest-rank"): the smallest sample
// x such that at least p percent of the samples are <= x, i.e. the ceil(p n / 100)-th smallest
// (1-based; the smallest for p = 0). Always an actual sample, so p100 == max. Exact and
// independent of the input order. p in [0, 100] (clamped); empty input -> NaN.
// O(n) (std::nth_element on a copy).
double percentile_nearest_rank(std::span<const double> samples, double p);
double percentile_nearest_rank(std::span<const float> samples, double p);

// 0-based index of the nearest-rank percentile in a sorted sequence of n >= 1 samples.
std::size_t nearest_rank_index(std::size_t n, double p);

// Arithmetic mean (NaN when empty), summed in input order.
double mean_of(std::span<const double> samples);

// A sample with a weight >= 0, for the weighted percentile.
struct WeightedSample {
  float value = 0.0f;
  float weight = 0.0f;
};

// Weighted nearest-rank percentile: the smallest sample value x such that the samples <= x
// carry at least p percent of the total weight. With equal weights it is the nearest-rank
// percentile above (up to the rounding of the weight sums). Zero-weight samples never count;
// NaN without positive weight. Sorts `samples` in place (by value, then weight: the result does
// not depend on the input order). p in [0, 100] (clamped).
double weighted_percentile(std::span<WeightedSample> samples, double p);

// The 95 % confidence interval of a mean by the percentile bootstrap (Efron & Tibshirani 1993,
// ch. 13): `resamples` resamples of the values with replacement, drawn from a counter-based
// generator seeded by `seed` (the same inputs give the same interval, on any machine), the 2.5th
// and 97.5th nearest-rank percentiles of the resampled means. One value gives [x, x]; no value
// gives NaNs.
struct Interval {
  double low = 0.0;
  double high = 0.0;
};
Interval bootstrap_mean_interval(std::span<const double> values, std::uint64_t seed,
                                 int resamples = 10000);

}  // namespace ambisim
