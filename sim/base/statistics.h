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

}  // namespace ambisim
