#include "sim/metrics/response_time.h"

#include <algorithm>

#include "sim/base/statistics.h"
#include "sim/colour/ciede2000.h"

namespace ambisim {

ResponseTracker::ResponseTracker(ResponseSettings settings) : settings_(settings) {}

void ResponseTracker::update(std::uint64_t id, std::int64_t frame, double time,
                             std::span<const Lab> reference, double planner_error_de) {
  State& s = receivers_[id];
  s.frame = frame;
  s.last_time = time;
  // The oldest sample still within the window is the one compared against (1e-9 s of slack:
  // frame times are sums of steps).
  while (!s.history.empty() && time - s.history.front().time > settings_.window_s + 1e-9) {
    s.history.pop_front();
  }
  double moved = 0.0;
  if (!s.history.empty()) {
    const std::vector<Lab>& then = s.history.front().reference;
    for (std::size_t n = 0; n < reference.size() && n < then.size(); ++n) {
      moved = std::max(moved, ciede2000(reference[n], then[n]));
    }
  }
  s.history.push_back({time, std::vector<Lab>(reference.begin(), reference.end())});
  if (!s.open && moved > settings_.event_de &&
      time - s.last_opened_at >= settings_.window_s - 1e-12) {
    s.open = true;
    s.opened_at = time;
    s.last_opened_at = time;
  }
  if (s.open && planner_error_de < settings_.settled_de) {
    closed_.push_back(time - s.opened_at);
    s.open = false;
  }
}

void ResponseTracker::censor(State& s) {
  if (!s.open) return;
  closed_.push_back(s.last_time - s.opened_at);
  ++censored_;
  s.open = false;
}

void ResponseTracker::end_frame(std::int64_t frame) {
  for (auto it = receivers_.begin(); it != receivers_.end();) {
    if (it->second.frame != frame) {
      censor(it->second);
      it = receivers_.erase(it);
    } else {
      ++it;
    }
  }
}

std::vector<double> ResponseTracker::times() const {
  std::vector<double> t = closed_;
  for (const auto& [id, s] : receivers_) {
    if (s.open) t.push_back(s.last_time - s.opened_at);
  }
  return t;
}

ResponseSummary ResponseTracker::summary() const {
  ResponseSummary r;
  const std::vector<double> t = times();
  r.events = static_cast<std::int64_t>(t.size());
  r.censored = censored_;
  for (const auto& [id, s] : receivers_) r.censored += s.open ? 1 : 0;
  r.median_s = percentile_nearest_rank(std::span<const double>(t), 50.0);
  r.p95_s = percentile_nearest_rank(std::span<const double>(t), 95.0);
  return r;
}

}  // namespace ambisim
