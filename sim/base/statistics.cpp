#include "sim/base/statistics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "sim/base/hash.h"

namespace ambisim {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

template <typename T>
double percentile_of(std::span<const T> samples, double p) {
  if (samples.empty()) return kNaN;
  std::vector<T> v(samples.begin(), samples.end());
  const std::size_t k = nearest_rank_index(v.size(), p);
  // nth_element places exactly the k-th order statistic at k, whatever its internal pivots.
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return static_cast<double>(v[k]);
}

}  // namespace

void RunningStats::add(double x) {
  if (count_ == 0) {
    max_ = x;
    min_ = x;
  } else {
    max_ = std::max(max_, x);
    min_ = std::min(min_, x);
  }
  sum_ += x;
  ++count_;
}

double RunningStats::mean() const {
  return count_ == 0 ? kNaN : sum_ / static_cast<double>(count_);
}
double RunningStats::max() const { return count_ == 0 ? kNaN : max_; }
double RunningStats::min() const { return count_ == 0 ? kNaN : min_; }

void TimeWeightedMean::add(double x, double weight) {
  weighted_sum_ += x * weight;
  weight_ += weight;
}

double TimeWeightedMean::mean() const { return weight_ > 0.0 ? weighted_sum_ / weight_ : kNaN; }

std::size_t nearest_rank_index(std::size_t n, double p) {
  const double pc = std::clamp(p, 0.0, 100.0);
  // p * n first: for integer p the product is exact, so p95 of 20 samples is rank 19, not 20
  // (0.95 * 20 rounds to 19.000000000000004 and its ceil would be 20).
  const double rank = std::ceil(pc * static_cast<double>(n) / 100.0);
  const auto r = static_cast<std::size_t>(std::max(rank, 1.0));
  return std::min(r, n) - 1;
}

double percentile_nearest_rank(std::span<const double> samples, double p) {
  return percentile_of(samples, p);
}

double percentile_nearest_rank(std::span<const float> samples, double p) {
  return percentile_of(samples, p);
}

double mean_of(std::span<const double> samples) {
  if (samples.empty()) return kNaN;
  double s = 0.0;
  for (double x : samples) s += x;
  return s / static_cast<double>(samples.size());
}

double weighted_percentile(std::span<WeightedSample> samples, double p) {
  double total = 0.0;
  for (const auto& s : samples) total += s.weight > 0.0f ? static_cast<double>(s.weight) : 0.0;
  if (!(total > 0.0)) return kNaN;
  std::sort(samples.begin(), samples.end(), [](const WeightedSample& a, const WeightedSample& b) {
    return a.value < b.value || (a.value == b.value && a.weight < b.weight);
  });
  const double need = std::clamp(p, 0.0, 100.0) / 100.0 * total;
  double cumulative = 0.0;
  double last = kNaN;
  for (const auto& s : samples) {
    if (!(s.weight > 0.0f)) continue;
    cumulative += static_cast<double>(s.weight);
    last = s.value;
    if (cumulative >= need) return s.value;
  }
  return last;  // rounding left the sum a hair short of `need`: the largest weighted sample
}

Interval bootstrap_mean_interval(std::span<const double> values, std::uint64_t seed,
                                 int resamples) {
  const std::size_t n = values.size();
  if (n == 0) return {kNaN, kNaN};
  if (n == 1) return {values[0], values[0]};
  std::vector<double> means(static_cast<std::size_t>(std::max(resamples, 1)));
  for (std::size_t r = 0; r < means.size(); ++r) {
    double sum = 0.0;
    for (std::size_t k = 0; k < n; ++k) {
      const std::uint64_t h = splitmix64(hash_combine(hash_combine(seed, r), k));
      sum += values[static_cast<std::size_t>(h % n)];  // n is tiny: the modulo bias is ~n/2^64
    }
    means[r] = sum / static_cast<double>(n);
  }
  return {percentile_nearest_rank(std::span<const double>(means), 2.5),
          percentile_nearest_rank(std::span<const double>(means), 97.5)};
}

}  // namespace ambisim
