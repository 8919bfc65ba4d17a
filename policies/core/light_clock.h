#pragma once
// The thesis' refresh rule (7.5.3): "if one can predict the maximum rate at which the relevant
// lighting changes, one can also give the slowest rate at which coefficients must be
// regenerated". A LightClock measures a set's age in lifetime-equivalent seconds: it runs at
// real speed while the light is still and faster when the world reports change, at
// max(1, rate x lifetime_s / tolerance). A set expiring at clock age lifetime_s therefore lasts
// lifetime_s of real time under still light and tolerance / rate seconds while the light
// changes at `rate` (LightingInfo::change_rate, 1/s: the largest relative change anywhere),
// integrated over the set's life when the rate varies.
//
// Disabled (refresh=lifetime, or a world whose light never changes) it is real time exactly:
// ages are now - t, bit for bit what the planners computed before it existed.
#include <deque>
#include <string>
#include <utility>
#include <vector>

#include "policies/core/planner_params.h"
#include "sim/planner.h"

namespace ambisim {

class LightClock {
 public:
  LightClock() = default;
  // lifetime_s > 0, tolerance > 0: the relative change a set may go stale by.
  LightClock(bool enabled, double lifetime_s, double tolerance);

  // Once per frame, from the planner's update().
  void advance(const FrameContext& ctx);
  bool running() const { return running_; }
  // Clock age of data captured at real time t (t <= the last frame's time).
  double age(double t) const;
  // How many clock seconds a real second is now (1 under still light).
  double speed() const { return speed_; }

 private:
  double clock_at(double t) const;

  bool enabled_ = false;
  double lifetime_s_ = 60.0;
  double tolerance_ = 0.04;
  bool running_ = false;  // enabled and the world's light changes
  double now_ = 0.0;      // real time of the last frame
  double clock_ = 0.0;    // clock at now_
  double speed_ = 1.0;
  // (real time, clock) of past frames, to date data captured then; kept as long as data can
  // live (the clock's age of the oldest entry stays below 2 lifetimes).
  std::deque<std::pair<double, double>> history_;
};

// The parameters every planner with the rule takes: refresh (rate | lifetime, the default
// given) and refresh_tolerance.
std::vector<ParamSpec> light_clock_params(const std::string& default_refresh);
LightClock light_clock_from(const PlannerParams& params, double lifetime_s);

}  // namespace ambisim
