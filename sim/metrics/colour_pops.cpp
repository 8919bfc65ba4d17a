#include "sim/metrics/colour_pops.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "sim/colour/ciede2000.h"

namespace ambisim {

double unexplained_change(const Lab& planner_prev, const Lab& planner_now,
                          const Lab& reference_prev, const Lab& reference_now) {
  return ciede2000(planner_now, planner_prev + (reference_now - reference_prev));
}

PopTracker::PopTracker(double threshold_de) : threshold_(threshold_de) {}

PopEvaluation PopTracker::update(std::uint64_t id, std::int64_t frame, std::span<const Lab> planner,
                                 std::span<const Lab> reference) {
  if (planner.size() != reference.size()) {
    throw std::invalid_argument("colour pops: planner and reference normal counts differ");
  }
  PopEvaluation ev;
  auto it = last_.find(id);
  if (it != last_.end()) {
    State& s = it->second;
    if (s.frame == frame) {
      throw std::logic_error("colour pops: receiver " + std::to_string(id) +
                             " evaluated twice in frame " + std::to_string(frame));
    }
    if (s.frame == frame - 1 && s.planner.size() == planner.size()) {
      ev.has_previous = true;
      for (std::size_t n = 0; n < planner.size(); ++n) {
        ev.change = std::max(
            ev.change, unexplained_change(s.planner[n], planner[n], s.reference[n], reference[n]));
      }
      ev.pop = ev.change > threshold_;
    }
  } else {
    it = last_.emplace(id, State{}).first;
  }
  State& s = it->second;
  s.frame = frame;
  s.planner.assign(planner.begin(), planner.end());
  s.reference.assign(reference.begin(), reference.end());
  return ev;
}

void PopTracker::end_frame(std::int64_t frame) {
  std::erase_if(last_, [frame](const auto& kv) { return kv.second.frame != frame; });
}

}  // namespace ambisim
