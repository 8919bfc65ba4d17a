#pragma once
// SHGraph's settings and the thesis' rule D2 for the working depth (thesis 8.4.2, Bilaga B):
// the parameters every SHGraph planner shares (per dimension) and what they mean.
#include <vector>

#include "policies/core/coefficient_format.h"
#include "policies/core/planner_params.h"
#include "policies/core/velocity_prediction.h"
#include "policies/thesis/coefficient_anchor.h"

namespace ambisim {

enum class WeightMode { inverse_distance, compact };
enum class LevelRule { first, complete };
// Which missing cells go first. near_first: the working depth around the (predicted) camera
// before any coarser cell, inside the 3^Dim neighbourhood the thesis' split priority (centre,
// the 8 corners, the 6 faces, the 12 edges; L572), then by distance (L562, L566: "high
// resolution around the camera before far nodes"). coarse_first: every coarser missing cell
// first (the first version's order, kept to measure against).
enum class CandidateOrder { near_first, coarse_first };
// Where the 3D lattice's vertical origin stands. ground: a cell centre of every depth at
// anchor_height_m above the ground under the first camera position (the engine's sets "a bit
// above the ground", L592). camera: at the first camera position.
enum class LatticeAnchor { ground, camera };

struct ShGraphSettings {
  double root_size_m = 243.0;   // the normal root size (D9); cells are root / 3^d
  double min_cell_m = 3.0;      // finest cell: MaxDepth = floor(log3(root / min_cell)) (D2)
  double k = 9.0;               // D2: cells exposed per finest cell crossed (9 in 3D, 3 on a sheet)
  double fps_min = 0.0;         // D2 frame rate; 0 = the current one (1 / dt)
  AnchorTiming timing;          // lifetime, fade; margin is derived per frame (D7)
  bool refresh_by_rate = true;  // the thesis' refresh rule under changing light (7.5.3)
  double refresh_tolerance = 0.04;  // the relative change a set may go stale by
  bool fade_from_lookup = true;     // D8: a fresh anchor fades from the lookup value (else snaps)
  // 7.6's remedy for pattern pops: a set that just appeared enters the interpolation weights
  // over pattern_blend_s, the rest of the weight staying with the coarser levels' answer, so
  // a new finer level (a new interpolation pattern) blends in instead of switching (0: off).
  double pattern_blend_s = 1.0;
  WeightMode weights = WeightMode::inverse_distance;  // D4
  LevelRule level = LevelRule::first;                 // D5 / L963
  int widen_cells = 3;  // widening radius at the working depth once 3^Dim is complete
  CandidateOrder order = CandidateOrder::near_first;
  // Budget left after the neighbourhood and the widening: keep widening ring by ring at
  // max(working depth, 1), one cell up and down, inside the root (L574: going a level up at
  // speed "generates new coefficients there"; the budget is granted either way).
  bool fill_budget = true;
  int fill_cells = 6;            // at most this many rings (cells) out
  double fill_radius_m = 243.0;  // and no farther from the focus than this
  LatticeAnchor anchor = LatticeAnchor::ground;
  double anchor_height_m = 2.0;  // with anchor = ground
  // Road knowledge (L316), with route prediction on a road: the cells the road passes through
  // over the next road_ahead_s are captured road_refine_levels finer than the working depth,
  // before anything else (0 levels: off; the car will be there).
  int road_refine_levels = 0;
  double road_ahead_s = 2.0;
  // A set inside a solid (L318) moves up by at most this fraction of its cell, and its light is
  // attributed where it was captured; one deeper inside is never captured (DDGI relocation and
  // classification, never the nominal point).
  double max_relocation_cells = 0.5;
  double lift_m = 0.5;             // D14: captures at least this far above the surface
  bool skip_underground = true;    // L307: cells wholly below the terrain are never captured
  double sheet_height_m = 2.0;     // Dim = 2: sheet height above the ground (D12)
  bool sheet_over_surface = true;  // Dim = 2: above surface_height (else ground_height)
  double shrink_hold_s = 5.0;      // D9 hysteresis before a grown root shrinks back
  PredictionSettings prediction;   // +vp (D15)
  CoefficientFormat format;
};

// D2. Capture rate R = fps * faces / 6 sets/s; a camera crossing a finest cell of size s at
// speed v exposes k new cells to capture within s / v, so s >= k v / R.
double min_cell_for_speed(double speed_mps, double fps, double faces_per_frame, double k);
// floor(log3(root / max(s, min_cell))), clamped to [0, max_depth(root, min_cell)].
int max_depth(double root_size_m, double min_cell_m);
int depth_for_speed(double speed_mps, double fps, double faces_per_frame, const ShGraphSettings& s);

// The parameters shared by all SHGraph planners (defaults per dimension), and the settings
// they describe.
std::vector<ParamSpec> shgraph_params(int dim, bool predict, bool route);
ShGraphSettings shgraph_settings_from(const PlannerParams& p, int dim);

}  // namespace ambisim
