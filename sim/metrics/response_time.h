#pragma once
// Response time (SPEC section 5; the thesis' anchors' "frames to converge"): how long a
// planner takes to follow a true change of the lighting at a receiver.
// - A true-change event at a receiver opens when its truth has moved by more than event_de
//   (CIEDE2000, largest over the normals) within the last window_s: the reference now against
//   the reference window_s ago (or at the receiver's first frame, if younger).
// - Its response time is the time from that frame until the first frame at which the planner's
//   error there (the mean dE00 over the normals) is below settled_de: 0 when it already is.
// - An event still open when the receiver ends (despawns, or the run ends) is censored: its
//   time runs to the receiver's last frame and counts as such (a lower bound), and is counted
//   apart as `censored`.
// - Events at one receiver do not overlap and open at least window_s apart, so a long, steady
//   change (a sunset) is a sequence of events half a second apart, not one per frame.
#include <cstdint>
#include <deque>
#include <map>
#include <span>
#include <vector>

#include "sim/colour/cielab.h"

namespace ambisim {

struct ResponseSettings {
  double event_de = 5.0;
  double window_s = 0.5;
  double settled_de = 2.0;
};

struct ResponseSummary {
  std::int64_t events = 0;
  std::int64_t censored = 0;
  double median_s = 0.0;  // nearest-rank, censored times included (NaN without events)
  double p95_s = 0.0;
};

class ResponseTracker {
 public:
  explicit ResponseTracker(ResponseSettings settings = {});

  // Receiver `id` at `frame` (increasing per receiver) and `time`: its reference colours (one
  // per normal, the same count at every call) and the planner's error there now.
  void update(std::uint64_t id, std::int64_t frame, double time, std::span<const Lab> reference,
              double planner_error_de);
  // Ends the receivers not updated at `frame` (despawned): their open events are censored.
  void end_frame(std::int64_t frame);
  // The summary so far, open events censored at their receivers' last frames.
  ResponseSummary summary() const;
  // Every closed or censored response time so far, in the order they ended (for tests).
  std::vector<double> times() const;

 private:
  struct Sample {
    double time;
    std::vector<Lab> reference;
  };
  struct State {
    std::int64_t frame = 0;
    double last_time = 0.0;
    std::deque<Sample> history;  // samples within window_s, oldest first
    bool open = false;
    double opened_at = 0.0;
    double last_opened_at = -1e300;
  };
  void censor(State& s);

  ResponseSettings settings_;
  std::map<std::uint64_t, State> receivers_;
  std::vector<double> closed_;
  std::int64_t censored_ = 0;
};

}  // namespace ambisim
