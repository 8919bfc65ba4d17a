#include "policies/core/light_clock.h"

#include <algorithm>
#include <iterator>

namespace ambisim {

LightClock::LightClock(bool enabled, double lifetime_s, double tolerance)
    : enabled_(enabled), lifetime_s_(lifetime_s), tolerance_(tolerance) {}

void LightClock::advance(const FrameContext& ctx) {
  const WorldQueries* w = ctx.world;
  if (!running_) {
    running_ = enabled_ && w != nullptr && !w->lighting_static && w->lighting;
    if (running_) {
      clock_ = ctx.time;  // real time until now: the light was still before
      history_.push_back({ctx.time, clock_});
    }
    now_ = ctx.time;
    return;
  }
  const double dt = ctx.time - now_;
  if (dt > 0.0) {
    // The rate over the step: the world's at the step's end (an engine's schedule).
    const double rate = w->lighting(ctx.time).change_rate;
    speed_ = std::max(1.0, rate * lifetime_s_ / tolerance_);
    clock_ += speed_ * dt;
    now_ = ctx.time;
    history_.push_back({now_, clock_});
  }
  while (history_.size() > 2 && clock_ - history_[1].second > 2.0 * lifetime_s_) {
    history_.pop_front();
  }
}

double LightClock::clock_at(double t) const {
  if (history_.empty() || t <= history_.front().first) {
    // Before the history: the clock ran at real speed up to its first entry, or the entry is
    // older than any data can live.
    return history_.empty() ? t : history_.front().second - (history_.front().first - t);
  }
  if (t >= history_.back().first) return history_.back().second + (t - history_.back().first);
  const auto hi = std::lower_bound(history_.begin(), history_.end(), t,
                                   [](const auto& e, double x) { return e.first < x; });
  const auto lo = std::prev(hi);
  const double f = (t - lo->first) / (hi->first - lo->first);
  return lo->second + f * (hi->second - lo->second);
}

double LightClock::age(double t) const {
  if (!running_) return now_ - t;
  return clock_ - clock_at(t);
}

std::vector<ParamSpec> light_clock_params(const std::string& default_refresh) {
  return {choice_param("refresh", default_refresh, {"rate", "lifetime"},
                       "rate: the thesis' rule (7.5.3), sets are renewed when the light may have "
                       "changed by refresh_tolerance (after refresh_tolerance / rate seconds at "
                       "the world's rate, at most lifetime_s); lifetime: after lifetime_s"),
          number_param("refresh_tolerance", 0.04, Range::positive(),
                       "refresh=rate: the relative change of the light a set may go stale by "
                       "(0.04: about 1 dE00 at mid-grey)")};
}

LightClock light_clock_from(const PlannerParams& params, double lifetime_s) {
  return LightClock(params.choice("refresh") == "rate", lifetime_s,
                    params.number("refresh_tolerance"));
}

}  // namespace ambisim
