#pragma once
// When frames happen. The frame rate is piecewise constant or ramps linearly; frame k is at
// the time where the frame count N(t) = integral of fps dt reaches k. N is continuous, so a
// rate change never double-counts or skips a frame, and each frame time is computed from its
// integer index (not by summing dt), so times never drift.
#include <cstdint>
#include <vector>

#include "sim/base/json_reader.h"

namespace ambisim {

struct FpsSegment {
  double from_s = 0.0;        // start time (s); the first segment starts at 0
  double fps = 60.0;          // frames per second, > 0
  bool ramp_to_next = false;  // fps changes linearly to the next segment's fps at its from_s
};

struct FrameScheduleRecord {
  std::vector<FpsSegment> segments;  // non-empty, from_s strictly increasing, first at 0
  double duration_s = 10.0;          // frames are generated for times < duration_s
};

// JSON ("frames" object):
//   duration_s  > 0 and <= 86400, seconds simulated; at most 1e6 frames in all    [10]
//   fps         > 0 and <= 10000, constant frame rate                            [60]
//   segments    [{"from_s" >= 0 (first must be 0), "fps" > 0, "ramp_to_next" [false]}]
//               instead of fps; from_s strictly increasing; the last may not ramp.
FrameScheduleRecord parse_frame_schedule(ObjectReader& r);

struct Frame {
  std::int64_t index = 0;
  double time = 0.0;  // s
  double dt = 0.0;    // s since the previous frame; frame 0 gets 1 / fps(0)
};

class FrameSchedule {
 public:
  explicit FrameSchedule(FrameScheduleRecord record);

  double fps_at(double t) const;         // t >= 0
  double frames_before(double t) const;  // N(t), t >= 0
  double time_of(std::int64_t k) const;  // N^{-1}(k), k >= 0
  Frame frame(std::int64_t k) const;
  double duration() const { return duration_; }
  // Number of frames with time < duration.
  std::int64_t frame_count() const { return count_; }

 private:
  struct Piece {
    double t0, t1, f0, g, n0;  // fps = f0 + g (t - t0) on [t0, t1); n0 = N(t0)
  };
  std::vector<Piece> pieces_;
  double duration_;
  std::int64_t count_ = 0;
};

// Yields the frames of a schedule in order: `while (clock.next(f)) { ... }`.
class FrameClock {
 public:
  explicit FrameClock(const FrameSchedule& schedule) : schedule_(&schedule) {}
  bool next(Frame& out);

 private:
  const FrameSchedule* schedule_;
  std::int64_t k_ = 0;
};

}  // namespace ambisim
