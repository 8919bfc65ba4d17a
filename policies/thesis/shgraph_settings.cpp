#include "policies/thesis/shgraph_settings.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ambisim {
namespace {

// Cells of `size` from `root` down while they stay >= `floor_m` (integer steps, so 243 / 27
// gives exactly 2 levels without log rounding), at most `limit` levels.
int levels_down(double root, double floor_m, int limit) {
  int d = 0;
  double size = root;
  while (d < limit && size / 3.0 >= floor_m * (1.0 - 1e-9)) {
    size /= 3.0;
    ++d;
  }
  return d;
}

}  // namespace

double min_cell_for_speed(double speed_mps, double fps, double faces_per_frame, double k) {
  const double rate = fps * faces_per_frame / 6.0;  // sets per second
  if (rate <= 0.0) return std::numeric_limits<double>::infinity();
  return k * speed_mps / rate;
}

int max_depth(double root_size_m, double min_cell_m) {
  return levels_down(root_size_m, min_cell_m, 20);  // 3^20 still fits the int64 keys (D10)
}

int depth_for_speed(double speed_mps, double fps, double faces_per_frame,
                    const ShGraphSettings& s) {
  const double need =
      std::max(min_cell_for_speed(speed_mps, fps, faces_per_frame, s.k), s.min_cell_m);
  if (!std::isfinite(need)) return 0;
  return levels_down(s.root_size_m, need, max_depth(s.root_size_m, s.min_cell_m));
}

std::vector<ParamSpec> shgraph_params(int dim, bool predict, bool route) {
  std::vector<ParamSpec> v = {
      number_param("lifetime_s", 60.0, Range::positive(),
                   "a set is valid this long after its capture was requested (D6)"),
      number_param("fade_s", 1.0, Range::non_negative(),
                   "new coefficients fade in linearly over this time (D8)"),
      choice_param("fade_from", "lookup", {"lookup", "none"},
                   "a fresh anchor fades from what lookups gave there (lookup) or snaps (none)"),
      number_param("pattern_blend_s", 1.0, Range::non_negative(),
                   "7.6: a new set enters the weights over this time, the rest staying with the "
                   "coarser levels (0: the pattern switches at once)"),
      number_param("root_size_m", 243.0, Range::positive(),
                   "normal root cell size; grows 3x to capture outside it, shrinks back (D9)"),
      number_param("min_cell_m", 3.0, Range::positive(),
                   "finest cell: max depth = floor(log3(root_size_m / min_cell_m)) (D2)"),
      number_param("k", dim == 3 ? 9.0 : 3.0, Range::positive(),
                   "D2: working cell >= k * speed / (fps * faces / 6); cells exposed per cell "
                   "crossed"),
      number_param("fps_min", 0.0, Range::non_negative(),
                   "frame rate for D2 (the minimum expected); 0 = the current frame rate"),
      choice_param("weights", "inverse", {"inverse", "compact"},
                   "D4: 1/distance, or max(0, 1 - d / (2 cells)) (pops less when sets enter)"),
      choice_param("level", "first", {"first", "complete"},
                   "lookup level: first with any set (L963), or first with every octant filled"),
      integer_param("widen_cells", 3, Range::closed(1, 5),
                    "widen the working-depth region up to this radius once 3^dim is complete"),
      choice_param("candidate_order", "near_first", {"near_first", "coarse_first"},
                   "missing cells: the working depth first, centre/corners/faces/edges (L562, "
                   "L572), or every coarser cell first"),
      bool_param("fill_budget", true,
                 "budget left: keep widening ring by ring at max(working depth, 1) (L574)"),
      integer_param("fill_cells", 6, Range::closed(0, 27),
                    "with fill_budget: at most this many rings (cells) out"),
      number_param("fill_radius_m", 243.0, Range::non_negative(),
                   "with fill_budget: and at most this far from the focus"),
      number_param("max_relocation_cells", 0.5, Range::non_negative(),
                   "a set inside a solid moves up by at most this many cells, else it is never "
                   "captured (L318)"),
      bool_param("predict", predict,
                 "plan around the predicted camera (+vp: latency + lookahead_s ahead, D15)"),
      number_param("lookahead_s", 0.5, Range::non_negative(),
                   "prediction beyond the capture latency (D15)"),
      bool_param("route", route, "predict along the road spline when on it (thesis 7.5.3)"),
      integer_param("road_refine_levels", route ? 1 : 0, Range::closed(0, 3),
                    "with route: the road ahead this many levels finer than the working depth "
                    "(L316)"),
      number_param("road_ahead_s", 2.0, Range::non_negative(),
                   "with road_refine_levels: how far ahead along the road, in seconds"),
  };
  if (dim == 3) {
    v.push_back(number_param("lift_m", 0.5, Range::non_negative(),
                             "captures at least this far above the surface (canopy) (D14)"));
    v.push_back(bool_param("skip_underground", true,
                           "never capture cells wholly below the terrain (floor, L307)"));
    v.push_back(choice_param("lattice_anchor", "ground", {"ground", "camera"},
                             "the lattice's vertical origin: a cell centre anchor_height_m above "
                             "the ground (L592) or at the first camera position"));
    v.push_back(number_param("anchor_height_m", 2.0, Range::non_negative(),
                             "with lattice_anchor=ground: the cell centres' height"));
  } else {
    v.push_back(number_param("height_m", 2.0, Range::non_negative(),
                             "sheet height above the ground (D12)"));
    v.push_back(choice_param("sheet_over", "surface", {"ground", "surface"},
                             "sheet follows the canopy top, or the terrain (under a canopy the "
                             "sheet's cells stand inside it and are dropped)"));
  }
  for (auto& p : light_clock_params("rate")) v.push_back(std::move(p));
  for (auto& p : coefficient_format_params()) v.push_back(std::move(p));
  return v;
}

ShGraphSettings shgraph_settings_from(const PlannerParams& p, int dim) {
  ShGraphSettings s;
  s.timing.lifetime_s = p.number("lifetime_s");
  s.timing.fade_s = p.number("fade_s");
  s.refresh_by_rate = p.choice("refresh") == "rate";
  s.refresh_tolerance = p.number("refresh_tolerance");
  s.fade_from_lookup = p.choice("fade_from") == "lookup";
  s.pattern_blend_s = p.number("pattern_blend_s");
  s.root_size_m = p.number("root_size_m");
  s.min_cell_m = std::min(p.number("min_cell_m"), s.root_size_m);
  s.k = p.number("k");
  s.fps_min = p.number("fps_min");
  s.weights = p.choice("weights") == "compact" ? WeightMode::compact : WeightMode::inverse_distance;
  s.level = p.choice("level") == "complete" ? LevelRule::complete : LevelRule::first;
  s.widen_cells = static_cast<int>(p.integer("widen_cells"));
  s.order = p.choice("candidate_order") == "coarse_first" ? CandidateOrder::coarse_first
                                                          : CandidateOrder::near_first;
  s.fill_budget = p.boolean("fill_budget");
  s.fill_cells = static_cast<int>(p.integer("fill_cells"));
  s.fill_radius_m = p.number("fill_radius_m");
  s.max_relocation_cells = p.number("max_relocation_cells");
  s.road_refine_levels = static_cast<int>(p.integer("road_refine_levels"));
  s.road_ahead_s = p.number("road_ahead_s");
  s.prediction.enabled = p.boolean("predict");
  s.prediction.lookahead_s = p.number("lookahead_s");
  s.prediction.route = p.boolean("route");
  if (dim == 3) {
    s.lift_m = p.number("lift_m");
    s.skip_underground = p.boolean("skip_underground");
    s.anchor =
        p.choice("lattice_anchor") == "camera" ? LatticeAnchor::camera : LatticeAnchor::ground;
    s.anchor_height_m = p.number("anchor_height_m");
  } else {
    s.sheet_height_m = p.number("height_m");
    s.sheet_over_surface = p.choice("sheet_over") == "surface";
    s.skip_underground = false;
  }
  s.format = coefficient_format_from(p);
  return s;
}

}  // namespace ambisim
