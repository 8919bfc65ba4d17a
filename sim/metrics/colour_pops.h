#pragma once
// Colour pops (SPEC section 5): the frame-to-frame change of a receiver's displayed ambient
// colour that the reference does not explain.
//
// For one receiver and normal, with P_t and R_t the displayed colours (CIELAB, after the fixed
// exposure and tone map) of the planner's and the reference irradiance at frame t:
//   unexplained change  u_t = ciede2000(P_t, P_{t-1} + (R_t - R_{t-1}))
// i.e. the distance from where the planner is to where it would be had it moved exactly as the
// true lighting did (the Lab difference carried over component-wise). A planner that tracks the
// reference, however wrong in absolute terms, scores 0; so does one that is constant while the
// reference is constant.
//
// Per receiver and frame the change is the largest u_t over the normals; it is a pop when it
// exceeds the threshold (one just-noticeable difference, dE00 = 1). A receiver-frame counts as
// at most one pop even when several normals exceed it (one object visibly changing once is one
// event). A receiver's first frame, and its first frame after missing one or more frames, has
// no previous value and can never pop.
#include <cstdint>
#include <map>
#include <span>
#include <vector>

#include "sim/colour/cielab.h"

namespace ambisim {

// u_t for one normal (any Lab values).
double unexplained_change(const Lab& planner_prev, const Lab& planner_now,
                          const Lab& reference_prev, const Lab& reference_now);

struct PopEvaluation {
  bool has_previous = false;  // false on a receiver's first (or first-after-gap) frame
  double change = 0.0;        // max over normals of u_t (0 without a previous frame)
  bool pop = false;           // change > threshold
};

// Remembers each receiver's displayed colours from its last frame. Keyed by receiver id in an
// ordered map; only lookups and erasures, so no result depends on iteration order.
class PopTracker {
 public:
  explicit PopTracker(double threshold_de);

  // Evaluates receiver `id` at `frame` and stores its colours for the next frame. planner and
  // reference hold one Lab per normal, the same count for every call of a receiver.
  // Frames must increase by 1 for a pop to be possible; calling twice for the same id and
  // frame throws std::logic_error.
  PopEvaluation update(std::uint64_t id, std::int64_t frame, std::span<const Lab> planner,
                       std::span<const Lab> reference);

  // Drops receivers not updated at `frame` (despawned ones); call once at the end of a frame.
  void end_frame(std::int64_t frame);

  std::size_t tracked() const { return last_.size(); }
  double threshold() const { return threshold_; }

 private:
  struct State {
    std::int64_t frame = 0;
    std::vector<Lab> planner;
    std::vector<Lab> reference;
  };
  double threshold_;
  std::map<std::uint64_t, State> last_;
};

}  // namespace ambisim
