#pragma once
// The capture budget, counted in cube faces per frame (never timed). A fractional rate
// accumulates: 0.5 gives a face every other frame, 2.5 gives 2, 3, 2, 3, ... Unused budget
// carries over only as its fractional part plus at most max_carry_faces whole faces, so an
// idle planner cannot bank a burst (default: no whole faces carry).
#include <cstdint>
#include <vector>

#include "sim/base/json_reader.h"

namespace ambisim {

struct BudgetStep {
  double from_s = 0.0;           // s
  double faces_per_frame = 1.0;  // >= 0
};

struct CaptureBudgetRecord {
  double faces_per_frame = 1.0;      // used when schedule is empty
  std::vector<BudgetStep> schedule;  // piecewise constant over time; first from_s = 0
  int face_size = 16;                // cube face resolution (texels per side)
  int max_carry_faces = 0;           // whole unused faces that may carry to the next frame
};

// JSON ("budget" object):
//   faces_per_frame  >= 0 and <= 96, cube faces rendered per frame                    [1.0]
//   schedule         [{"from_s" >= 0 (first 0, strictly increasing), "faces_per_frame"}]
//                    instead of faces_per_frame                                          [none]
//   face_size        1..1024 texels                                                     [16]
//   max_carry_faces  0..96 whole faces that unused budget may carry over                [0]
CaptureBudgetRecord parse_capture_budget(ObjectReader& r);

struct BudgetCounters {
  std::int64_t frames = 0;
  std::int64_t requested = 0;  // faces asked for through grant()
  std::int64_t granted = 0;
  std::int64_t refused = 0;  // asked beyond the budget: requested - granted
};

class CaptureBudget {
 public:
  explicit CaptureBudget(CaptureBudgetRecord record);

  // Starts a frame at `time` (s): trims the carry, then adds this frame's allowance.
  void begin_frame(double time);
  int available() const;     // whole faces grantable now
  int grant(int requested);  // requested >= 0; returns min(requested, available())
  double faces_per_frame(double time) const;
  int face_size() const { return face_size_; }
  double credit() const { return credit_; }  // faces, including the fractional part
  const BudgetCounters& counters() const { return counters_; }

 private:
  std::vector<BudgetStep> schedule_;
  int face_size_;
  int max_carry_;
  double credit_ = 0.0;
  BudgetCounters counters_;
};

}  // namespace ambisim
