#include "sim/metrics/colour_pops.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "sim/colour/ciede2000.h"

namespace ambisim {

Lab explained_move(const Lab& dp, const Lab& dr) {
  const double rr = dr.L * dr.L + dr.a * dr.a + dr.b * dr.b;
  if (!(rr > 0.0)) return Lab{};  // the truth is still: nothing is explained
  const double k = std::clamp((dp.L * dr.L + dp.a * dr.a + dp.b * dr.b) / rr, 0.0, 1.0);
  return Lab{k * dr.L, k * dr.a, k * dr.b};
}

double unexplained_change(const Lab& planner_prev, const Lab& planner_now,
                          const Lab& reference_prev, const Lab& reference_now) {
  const Lab e = explained_move(planner_now - planner_prev, reference_now - reference_prev);
  return ciede2000(planner_now, planner_prev + e);
}

PopTracker::PopTracker(double threshold_de, double masking)
    : threshold_(threshold_de), masking_(masking) {}

PopEvaluation PopTracker::update(std::uint64_t id, std::int64_t frame, std::span<const Lab> planner,
                                 std::span<const Lab> reference,
                                 std::span<const double> visible_share) {
  if (planner.size() != reference.size() ||
      (!visible_share.empty() && visible_share.size() != planner.size())) {
    throw std::invalid_argument("colour pops: planner, reference and visibility counts differ");
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
      // The receiver's own true jump: its largest over the normals (the whole object changes).
      double true_jump = 0.0;
      if (masking_ > 0.0) {
        for (std::size_t n = 0; n < planner.size(); ++n) {
          true_jump = std::max(true_jump, ciede2000(reference[n], s.reference[n]));
        }
      }
      const double limit = std::max(threshold_, masking_ * true_jump);
      for (std::size_t n = 0; n < planner.size(); ++n) {
        const double u = unexplained_change(s.planner[n], planner[n], s.reference[n], reference[n]);
        const bool seen = !visible_share.empty() && visible_share[n] > 0.0;
        ev.change = std::max(ev.change, u);
        ev.pop = ev.pop || u > limit;
        if (seen) {
          ev.viewed_change = std::max(ev.viewed_change, u);
          ev.viewed_pop = ev.viewed_pop || u > limit;
        }
      }
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
