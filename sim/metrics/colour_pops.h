#pragma once
// Colour pops (SPEC section 5): a jump of a receiver's displayed ambient colour that the truth
// does not explain.
//
// For one receiver and normal, with P_t and R_t the displayed colours (CIELAB, after the fixed
// exposure and tone map) of the planner's and the reference irradiance at frame t, and the
// moves dP = P_t - P_{t-1}, dR = R_t - R_{t-1}:
//   explained move      E = dR clamp(dP . dR / |dR|^2, 0, 1)    (E = 0 when dR = 0)
//   unexplained change  u_t = ciede2000(P_t, P_{t-1} + E)
// The explained part of the planner's move is its projection on the truth's move, clamped to
// [0, 1] of it: following the truth wholly or in part explains the move; a move while the truth
// is still, against it, beyond it or across it does not. So a display that never changes never
// pops (u = 0 whatever the truth does), and a planner that does not follow a true change is
// scored by accuracy and response time, not by pops. (The first definition,
// ciede2000(P_t, P_{t-1} + dR), counted every true change a planner did not follow as a pop;
// it is retired.)
//
// A normal pops when u_t exceeds max(threshold, masking x J_t), J_t the receiver's true jump
// (the largest ciede2000(R_t, R_{t-1}) over its normals): one just-noticeable difference
// (dE00 = 1), raised while the object itself visibly jumps. That is temporal
// masking, the rise of the visibility threshold with the inter-frame change (Chou & Chen 1996;
// the JND profiles of video coding): a planner that follows a 26 dE00 shadow edge to within 2.5
// (an SH9 probe at the receiver does, measured on rock_circle: 1.5 dE00 unexplained on one
// side while the other side jumps 30) shows one jump, which the truth explains, not a jump and
// a pop. masking = 0 is the plain definition above. Per receiver and
// frame the change is the largest u_t over the normals considered, and the receiver-frame pops
// when any of them does; it counts as at most one pop even when several normals pop (one
// object visibly changing once is one event). A receiver's first frame, its first frame after
// missing one or more frames, and every receiver's frame after a camera cut (forget_all: the
// player sees a new shot, not a change) have no previous value and can never pop.
#include <cstdint>
#include <map>
#include <span>
#include <vector>

#include "sim/colour/cielab.h"

namespace ambisim {

// The explained part E of the planner's move dP given the truth's move dR (any Lab values).
Lab explained_move(const Lab& planner_move, const Lab& reference_move);

// u_t for one normal (any Lab values).
double unexplained_change(const Lab& planner_prev, const Lab& planner_now,
                          const Lab& reference_prev, const Lab& reference_now);

struct PopEvaluation {
  bool has_previous = false;  // false on a receiver's first (or first-after-gap) frame
  double change = 0.0;        // max over normals of u_t (0 without a previous frame)
  bool pop = false;           // some normal's u_t > its (masked) threshold
  // The same over the normals the camera sees (visible share > 0), for the viewed metrics; 0
  // and false when none is visible or no shares were given.
  double viewed_change = 0.0;
  bool viewed_pop = false;
};

// Remembers each receiver's displayed colours from its last frame. Keyed by receiver id in an
// ordered map; only lookups and erasures, so no result depends on iteration order.
class PopTracker {
 public:
  explicit PopTracker(double threshold_de, double masking = 0.0);

  // Evaluates receiver `id` at `frame` and stores its colours for the next frame. planner and
  // reference hold one Lab per normal, the same count for every call of a receiver;
  // visible_share is empty or holds each normal's visible share now (> 0: seen).
  // Frames must increase by 1 for a pop to be possible; calling twice for the same id and
  // frame throws std::logic_error.
  PopEvaluation update(std::uint64_t id, std::int64_t frame, std::span<const Lab> planner,
                       std::span<const Lab> reference, std::span<const double> visible_share = {});

  // Drops receivers not updated at `frame` (despawned ones); call once at the end of a frame.
  void end_frame(std::int64_t frame);
  // Forgets every receiver (a camera cut): the next frame is nobody's continuation.
  void forget_all() { last_.clear(); }

  std::size_t tracked() const { return last_.size(); }
  double threshold() const { return threshold_; }

 private:
  struct State {
    std::int64_t frame = 0;
    std::vector<Lab> planner;
    std::vector<Lab> reference;
  };
  double threshold_;
  double masking_;
  std::map<std::uint64_t, State> last_;
};

}  // namespace ambisim
