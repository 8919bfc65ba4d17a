#pragma once
// `cascades`: camera-centred scrolling clipmaps of probes (RTXGI infinite scrolling volumes,
// Lumen's radiance-cache clipmaps, Godot SDFGI's cascades). `levels` nested grids of nx x ny x
// nz probes; level L has spacing_m 2^L horizontally and vertical_spacing_m 2^L vertically, so
// each level covers twice the extent of the one inside it with the same probe count. Level 0
// alone is `grid` (policies/baselines/scrolling_grid.h) with DDGI's blending.
//
// Placement (per level, as grid). Each level's window is centred horizontally on its own
// lattice point nearest the camera (or the predicted focus with predict=true), so it scrolls by
// whole cells of its own spacing: probes keep their data under their lattice index and only
// the new slab needs capturing. Vertically its middle layer is the level's lattice height
// nearest ground_height(centre) + height_m; it moves only when that target drifts more than
// 0.75 of the level's vertical cell away (hysteresis). The lattices nest (a level's lattice
// points are lattice points of every finer level), so a capture at a point serves every level
// holding a probe there: plan() asks once and deliver() feeds them all.
//
// Validity (DDGI relocation and classification). A lattice point below surface_height (the
// terrain or the canopy top; its highest value within 1 m, plus a quarter of the relief there,
// because the renderer's columns are flat-topped cells) + clearance_m is moved straight up to that
// height if the move is at most 0.45 of the level's vertical cell (RTXGI's relocation limit,
// ProbeRelocationCS.hlsl: "normalizedOffset < 0.45"); otherwise it is inactive: never captured nor
// used (lookups renormalise over the other corners). So no capture point is ever inside terrain or
// canopy. Each lattice point found inactive when it enters a window counts six faces saved.
//
// Refresh (Lumen style). Each frame plan() asks for min(startable, candidate points) captures:
// never-captured probes first (nearest the focus first, finer levels first on ties); then by
// age x closeness, age / (1 + distance / the level's spacing), age counted from the probe's
// last request.
//
// Blending (DDGI hysteresis, policies/baselines/ddgi_blend.h). A probe's first capture is
// taken as is (no hysteresis on a newly scrolled probe; with fade_in=true it blends in from
// what lookups at its point returned before, as grid's arrivals do); later ones become its target
// and its value moves there each update() by DDGI's per-frame lerp at 60 Hz (hysteresis 0.97: a
// time constant of 0.55 s), faster after a big change (irradiance_threshold 0.25), brightening at
// most brightness_threshold (0.10) per frame. After 99.3 % of the way it snaps.
//
// Lookup. The finest level whose window (box of its lattice) contains p and which holds data
// at one of the 8 lattice points around p answers: trilinear over those corners, weights
// renormalised; spacing_m = that level's spacing. Within blend_cells of the level's horizontal
// window edge the answer blends linearly into the next coarser level's (Lumen/SDFGI clipmap
// blending; weight 1 at the edge), spacing_m the blend of both spacings; contributors beyond 8
// keep the 8 heaviest, renormalised. p outside every window: clamped to the coarsest window's
// box (DDGI's volume clamp) with fell_back = true and spacing_m = its spacing + the distance
// clamped. No corner with data at any level: the nearest probe with data, fell_back = true,
// spacing_m = its distance; no data at all: the default ambient.
#include <array>
#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <vector>

#include "policies/baselines/ddgi_blend.h"
#include "policies/core/coefficient_format.h"
#include "policies/core/planner_info.h"
#include "policies/core/planner_params.h"
#include "policies/core/velocity_prediction.h"
#include "sim/planner.h"

namespace ambisim {

class CascadesPlanner final : public Planner {
 public:
  static PlannerInfo info();
  explicit CascadesPlanner(const PlannerParams& params);

  std::string name() const override { return "cascades"; }
  nlohmann::json params() const override { return params_.to_json(); }

  std::vector<CaptureRequest> plan(const FrameContext& ctx) override;
  void started(std::uint64_t tag) override;
  void refused(std::uint64_t tag) override;
  void deliver(const FinishedProbe& probe) override;
  void update(const FrameContext& ctx) override;
  LookupResult lookup(const glm::dvec3& p) const override;
  PlannerStats stats() const override;
  void describe_nodes(std::vector<ProbeNodeView>& out) const override;

  using Key = std::array<std::int64_t, 3>;        // lattice index (i, j, k) within a level
  static constexpr double kMaxRelocation = 0.45;  // of a vertical cell (RTXGI)

  // For tests.
  int level_count() const { return static_cast<int>(levels_.size()); }
  double spacing_of(int level) const { return levels_.at(static_cast<std::size_t>(level)).s; }
  double vertical_spacing_of(int level) const {
    return levels_.at(static_cast<std::size_t>(level)).vs;
  }
  Key window_min(int level) const { return levels_.at(static_cast<std::size_t>(level)).lo; }
  Key window_max(int level) const { return levels_.at(static_cast<std::size_t>(level)).hi; }
  std::size_t probe_count(int level) const {
    return levels_.at(static_cast<std::size_t>(level)).probes.size();
  }
  bool is_active(int level, const Key& k) const;
  bool has_data(int level, const Key& k) const;
  // The capture point of an active probe (its lattice point, relocated).
  std::optional<glm::dvec3> capture_point(int level, const Key& k) const;
  std::optional<Sh9Rgb> value(int level, const Key& k) const;
  glm::dvec3 lattice_point(int level, const Key& k) const;
  // Cube faces not rendered because lattice points were inactive (six per point entering a
  // window inside terrain or canopy). PlannerStats has no field for it.
  std::int64_t faces_saved_by_inactive() const { return faces_saved_; }
  std::int64_t relocated_count() const { return relocated_; }

 private:
  struct Probe {
    glm::dvec3 position{0.0};  // capture point (lattice point, relocated)
    bool has_data = false;
    bool in_flight = false;
    bool blending = false;      // value moving towards target
    double last_request = 0.0;  // request time of its latest capture (refresh priority)
    std::uint64_t tag = 0;      // the capture its target came from (contributor id)
    Sh9Rgb value;               // what lookups see, as stored
    double value_time = 0.0;    // data time of `value`
    Sh9Rgb target;              // the latest capture, as stored
    double target_time = 0.0;   // its request time
    double remaining = 0.0;     // fraction of the blend still to go
  };
  struct Level {
    double s = 0.0;   // horizontal spacing
    double vs = 0.0;  // vertical spacing
    bool placed = false;
    Key centre{0, 0, 0};
    Key lo{0, 0, 0}, hi{-1, -1, -1};  // empty until the first plan()
    std::map<Key, Probe> probes;      // active lattice points of the window
  };
  struct Ref {
    int level;
    Key key;
    bool operator<(const Ref& o) const { return level != o.level ? level < o.level : key < o.key; }
    bool operator==(const Ref& o) const = default;
  };
  // One level's trilinear answer at p (p clamped to its box); nullopt: no corner with data.
  struct LevelAnswer {
    Sh9Rgb sh;
    double data_time = 0.0;
    std::array<Contributor, 8> contributors{};
    int count = 0;
    double outside = 0.0;  // distance p was clamped
  };
  std::optional<LevelAnswer> level_answer(const Level& lv, const glm::dvec3& p) const;
  bool inside(const Level& lv, const glm::dvec3& p) const;
  // Weight of the next coarser level at p inside `lv` (0 deep inside, 1 at the edge).
  double edge_blend(const Level& lv, const glm::dvec3& p) const;
  LookupResult nearest_fallback(const glm::dvec3& p) const;
  void place_window(Level& lv, const glm::dvec3& focus, const FrameContext& ctx);
  Probe* find(const Ref& r);

  PlannerParams params_;
  CoefficientFormat format_;
  std::int64_t nx_, ny_, nz_;
  double height_m_;
  double clearance_m_;
  double blend_cells_;
  bool fade_in_;
  DdgiBlendSettings blend_;
  PredictionSettings prediction_;

  double now_ = 0.0;
  double last_update_ = std::numeric_limits<double>::quiet_NaN();  // time of the last update()
  Focus focus_;
  std::vector<Level> levels_;
  std::uint64_t next_tag_ = 1;
  std::int64_t faces_saved_ = 0;
  std::int64_t relocated_ = 0;
  std::map<std::uint64_t, std::vector<Ref>> pending_;    // returned by plan(), not yet started
  std::map<std::uint64_t, std::vector<Ref>> in_flight_;  // started, not yet delivered
};

}  // namespace ambisim
