#pragma once
// `grid`: a camera-centred scrolling probe grid (DDGI / RTXGI style), the baseline a user would
// otherwise pick. nx x ny x nz probes on a world-fixed integer lattice (spacing_m horizontally,
// vertical_spacing_m vertically), so when the camera moves the window scrolls by whole cells:
// probes keep their data under their lattice index and only the new slab needs capturing.
//
// Placement. Horizontally the window is centred on the lattice point nearest the camera (or
// the predicted focus with predict=true). Vertically the middle layer is the lattice level
// nearest ground_height(centre) + height_m (default 1.5 m: where the camera and the objects
// are), so the box reaches about one vertical cell below the ground and the lowest demand
// points lie inside it. "Ground" is the solid top: terrain or canopy. That level moves only
// when the target drifts more than 0.75 of a vertical cell away (hysteresis, so rolling ground
// does not flush whole layers back and forth). A probe lower than kClearance_m above the solid
// top at its own x, y is captured up to half a vertical cell higher (DDGI's relocation), and
// one deeper inside is inactive (DDGI's classification: it would see only backfaces): never
// captured nor used, so a point just above the ground interpolates the probes above it.
//
// Refresh. Each frame plan() asks for min(startable, candidates) captures at the lattice
// points: never-captured probes first, nearest the focus first; then by staleness x
// closeness, age / (1 + distance / spacing_m), where age counts from the probe's last request.
//
// Blending (time-based hysteresis). A delivered capture becomes the probe's target; from the
// next update() the probe's value moves from what it showed then towards the target as
// value = target + (start - target) exp(-t / blend_s): DDGI's per-frame lerp(old, new, 1 - h)
// with h = exp(-dt / blend_s), independent of the frame rate. When the L0 luminance changes
// by more than big_change (relative), the time constant drops to big_change_blend_s (DDGI's
// "big change" rule). A probe's first capture fades in the same way from what lookups at its
// position returned just before (its neighbours, or the coarse fallback below), so arrivals do
// not pop; with no data anywhere it is taken as is (no fade from black). After 5 time
// constants (99.3 %) the fade ends and the start set is freed.
//
// Lookup. Trilinear over the 8 lattice points around p, weights renormalised over those with
// data; spacing_m = spacing_m (the grid's horizontal spacing). A point outside the window is
// clamped to the window's box (DDGI's volume clamp): the answer still comes from the edge
// probes, but fell_back = true and spacing_m = spacing_m + the distance clamped, because no
// probe of the grid's spacing is around it. No probe with data among the 8 (the budget rarely
// lets a grid fill, unlike DDGI's every-probe-every-frame updates): the nearest probe with data
// as a coarse answer, fell_back = true, spacing_m = its distance; none at all: black, inf.
#include <array>
#include <cstdint>
#include <map>
#include <vector>

#include "policies/core/coefficient_format.h"
#include "policies/core/planner_info.h"
#include "policies/core/planner_params.h"
#include "policies/core/velocity_prediction.h"
#include "sim/planner.h"

namespace ambisim {

class ScrollingGridPlanner final : public Planner {
 public:
  static PlannerInfo info();
  explicit ScrollingGridPlanner(const PlannerParams& params);

  std::string name() const override { return "grid"; }
  nlohmann::json params() const override { return params_.to_json(); }

  std::vector<CaptureRequest> plan(const FrameContext& ctx) override;
  void started(std::uint64_t tag) override;
  void refused(std::uint64_t tag) override;
  void deliver(const FinishedProbe& probe) override;
  void update(const FrameContext& ctx) override;
  LookupResult lookup(const glm::dvec3& p) const override;
  PlannerStats stats() const override;
  void describe_nodes(std::vector<ProbeNodeView>& out) const override;

  using Key = std::array<std::int64_t, 3>;  // lattice index (i, j, k)
  static constexpr double kClearance_m = 0.25;
  // For tests: the window's lattice bounds (inclusive) and the probes (active lattice points).
  Key window_min() const { return lo_; }
  Key window_max() const { return hi_; }
  std::size_t probe_count() const { return probes_.size(); }
  // Lattice points classified inactive (too deep in terrain or canopy) as the window scrolled.
  std::int64_t dropped_in_solids() const { return dropped_in_solids_; }
  bool has_data(const Key& k) const;
  glm::dvec3 position_of(const Key& k) const;

 private:
  struct Probe {
    bool has_data = false;
    bool in_flight = false;
    double last_request = 0.0;  // request time of its latest capture (refresh priority)
    std::uint64_t tag = 0;      // the capture its target came from (contributor id)
    Sh9Rgb target;              // the latest capture, as stored
    double target_time = 0.0;   // its request time (D6)
    // Fade from `start` (the value shown when the capture arrived) towards `target`.
    bool fading = false;
    bool fade_start_known = false;  // false: delivered, usable from the next update()
    double fade_start = 0.0;
    double tau = 0.0;
    Sh9Rgb start;
    double start_time = 0.0;  // data time shown at `start`
    double lift_m = 0.0;      // captured this far above its lattice point (out of a solid)
  };

  // Fade weight of the target (0: all start, 1: all target).
  double target_weight(const Probe& q) const;
  Sh9Rgb value_of(const Probe& q) const;
  // The coarse answer when no corner around p holds data: the nearest probe that does.
  LookupResult nearest_fallback(const glm::dvec3& p) const;
  double data_time_of(const Probe& q) const;
  // Moves the window to be centred on `focus` (whole cells), dropping probes that left it.
  void place_window(const glm::dvec3& focus, const FrameContext& ctx);

  PlannerParams params_;
  CoefficientFormat format_;
  std::int64_t nx_, ny_, nz_;
  double spacing_m_;
  double vertical_spacing_m_;
  double height_m_;
  double blend_s_;
  double big_change_;
  double big_change_blend_s_;
  PredictionSettings prediction_;

  double now_ = 0.0;
  Focus focus_;
  bool placed_ = false;
  Key centre_{0, 0, 0};
  Key lo_{0, 0, 0}, hi_{-1, -1, -1};  // empty until the first plan()
  std::uint64_t next_tag_ = 1;
  std::int64_t dropped_in_solids_ = 0;
  std::map<Key, Probe> probes_;             // active lattice points of the window
  std::map<std::uint64_t, Key> pending_;    // returned by plan(), not yet started
  std::map<std::uint64_t, Key> in_flight_;  // started, not yet delivered
};

}  // namespace ambisim
