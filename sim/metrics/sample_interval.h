#pragma once
// Confidence intervals for scores computed on a sample of the receivers (a game's load: the
// referee scores every k-th receiver of each kind, sim/scenario/receiver_sample.h).
//
// The unit of sampling is a receiver (its frames are correlated: a receiver badly lit in one
// frame is badly lit in the next), so the interval comes from a stratified cluster bootstrap:
// each replicate redraws, within every stratum (receiver kind), as many receivers as it
// scored, with replacement, and recomputes the ratio scores from their totals. The interval is
// the 2.5th and 97.5th percentile of the replicates (percentile bootstrap). Deterministic: the
// draws come from a counter-based hash of (seed, replicate, stratum, draw).
#include <cstdint>
#include <limits>
#include <map>
#include <span>
#include <vector>

#include "sim/base/statistics.h"

namespace ambisim {

// One scored receiver's totals over the run.
struct ReceiverTotals {
  int stratum = 0;
  double de_sum = 0.0;             // uniform dE00 over its accuracy samples
  std::int64_t samples = 0;        // its accuracy samples
  double viewed_de_sum = 0.0;      // sum of weight x dE00 over its seen accuracy samples
  double viewed_weight = 0.0;      // sum of those weights
  std::int64_t pops = 0;           // its receiver-frames that popped (uniform)
  double seconds = 0.0;            // its live time
  double viewed_pop_weight = 0.0;  // sum of screen weights of its frames that popped where seen
  double viewed_seconds = 0.0;     // sum of screen weight x dt
};

inline constexpr double kNoInterval = std::numeric_limits<double>::quiet_NaN();

// Interval (statistics.h) ends; NaN when not computed.
struct SampleIntervals {
  Interval de2000_mean{kNoInterval, kNoInterval};         // uniform mean dE00
  Interval de2000_viewed_mean{kNoInterval, kNoInterval};  // viewed mean dE00
  Interval pops_per_min{kNoInterval, kNoInterval};        // uniform pops per receiver-minute
  Interval pops_viewed_per_min{kNoInterval, kNoInterval};
};

// 95% intervals from `replicates` bootstrap replicates (>= 20). With fewer than 2 receivers
// in every stratum the intervals are NaN (nothing to resample).
SampleIntervals bootstrap_intervals(std::span<const ReceiverTotals> receivers, int replicates,
                                    std::uint64_t seed);

// Accumulates ReceiverTotals by receiver id as the metrics see the frames.
class ReceiverTally {
 public:
  ReceiverTotals& at(std::uint64_t id, int stratum);
  std::vector<ReceiverTotals> totals() const;  // in id order
  std::size_t size() const { return by_id_.size(); }

 private:
  std::map<std::uint64_t, ReceiverTotals> by_id_;
};

}  // namespace ambisim
