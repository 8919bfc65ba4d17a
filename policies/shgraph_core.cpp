#include "policies/shgraph_core.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <set>
#include <tuple>

#include <glm/geometric.hpp>

#include "policies/default_ambient.h"

namespace ambisim {
namespace {

// A std::map node holds the value plus three links and a colour word.
constexpr std::size_t kMapNodeOverhead = 4 * sizeof(void*);
constexpr double kInf = std::numeric_limits<double>::infinity();

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
  if (rate <= 0.0) return kInf;
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
      bool_param("predict", predict,
                 "plan around the predicted camera (+vp: latency + lookahead_s ahead, D15)"),
      number_param("lookahead_s", 0.5, Range::non_negative(),
                   "prediction beyond the capture latency (D15)"),
      bool_param("route", route, "predict along the road spline when on it (thesis 7.5.3)"),
  };
  if (dim == 3) {
    v.push_back(number_param("lift_m", 0.5, Range::non_negative(),
                             "captures at least this far above the surface (canopy) (D14)"));
    v.push_back(bool_param("skip_underground", true,
                           "never capture cells wholly below the terrain (floor, L307)"));
  } else {
    v.push_back(number_param("height_m", 2.0, Range::non_negative(),
                             "sheet height above the ground (D12)"));
    v.push_back(choice_param("sheet_over", "ground", {"ground", "surface"},
                             "sheet follows the terrain (under canopy) or the canopy top"));
  }
  for (auto& p : coefficient_format_params()) v.push_back(std::move(p));
  return v;
}

ShGraphSettings shgraph_settings_from(const PlannerParams& p, int dim) {
  ShGraphSettings s;
  s.timing.lifetime_s = p.number("lifetime_s");
  s.timing.fade_s = p.number("fade_s");
  s.fade_from_lookup = p.choice("fade_from") == "lookup";
  s.root_size_m = p.number("root_size_m");
  s.min_cell_m = std::min(p.number("min_cell_m"), s.root_size_m);
  s.k = p.number("k");
  s.fps_min = p.number("fps_min");
  s.weights = p.choice("weights") == "compact" ? WeightMode::compact : WeightMode::inverse_distance;
  s.level = p.choice("level") == "complete" ? LevelRule::complete : LevelRule::first;
  s.widen_cells = static_cast<int>(p.integer("widen_cells"));
  s.prediction.enabled = p.boolean("predict");
  s.prediction.lookahead_s = p.number("lookahead_s");
  s.prediction.route = p.boolean("route");
  if (dim == 3) {
    s.lift_m = p.number("lift_m");
    s.skip_underground = p.boolean("skip_underground");
  } else {
    s.sheet_height_m = p.number("height_m");
    s.sheet_over_surface = p.choice("sheet_over") == "surface";
    s.skip_underground = false;
  }
  s.format = coefficient_format_from(p);
  return s;
}

// ---------------------------------------------------------------------------------------------

template <int Dim>
ShGraphCore<Dim>::ShGraphCore(const ShGraphSettings& s) : s_(s) {
  dmax_ = ambisim::max_depth(s_.root_size_m, s_.min_cell_m);
  pow3_[0] = 1;
  for (int i = 1; i < kMaxLevels; ++i) pow3_[i] = 3 * pow3_[i - 1];
  h_ = s_.root_size_m / (2.0 * static_cast<double>(pow3_[dmax_]));
}

template <int Dim>
typename ShGraphCore<Dim>::Q ShGraphCore<Dim>::to_q(const glm::dvec3& p) const {
  Q q;
  for (int a = 0; a < Dim; ++a) q[a] = (p[a] - origin_[a]) / h_;
  return q;
}

template <int Dim>
bool ShGraphCore<Dim>::contains(std::int32_t i, const Q& q) const {
  const Node& n = nodes_[i];
  const double hf = static_cast<double>(half(n.depth));
  for (int a = 0; a < Dim; ++a) {
    const double rel = q[a] - static_cast<double>(n.key[a]);
    if (!(rel >= -hf && rel < hf)) return false;  // NaN-safe
  }
  return true;
}

template <int Dim>
int ShGraphCore<Dim>::child_containing(std::int32_t i, const Q& q) const {
  const Node& n = nodes_[i];
  const double t = static_cast<double>(half(n.depth + 1));
  int c = 0, stride = 1;
  for (int a = 0; a < Dim; ++a) {
    const double rel = q[a] - static_cast<double>(n.key[a]);
    c += (rel < -t ? 0 : (rel >= t ? 2 : 1)) * stride;
    stride *= 3;
  }
  return c;
}

template <int Dim>
double ShGraphCore<Dim>::ground_at(double x, double y) const {
  if (world_ == nullptr) return 0.0;
  if (s_.sheet_over_surface && world_->surface_height) return world_->surface_height(x, y);
  if (world_->ground_height) return world_->ground_height(x, y);
  return 0.0;
}

template <int Dim>
glm::dvec3 ShGraphCore<Dim>::anchor_position(const Key& key) const {
  glm::dvec3 p = origin_;
  for (int a = 0; a < Dim; ++a) p[a] = origin_[a] + static_cast<double>(key[a]) * h_;
  if constexpr (Dim == 2) p.z = ground_at(p.x, p.y) + s_.sheet_height_m;
  return p;
}

template <int Dim>
glm::dvec3 ShGraphCore<Dim>::capture_position(const glm::dvec3& nominal) const {
  glm::dvec3 c = nominal;
  if (world_ == nullptr) return c;
  if constexpr (Dim == 3) {
    if (world_->surface_height) c.z = std::max(c.z, world_->surface_height(c.x, c.y) + s_.lift_m);
  } else {
    // The sheet stays under the canopy (D12); only the terrain itself is solid for it.
    if (world_->ground_height) c.z = std::max(c.z, world_->ground_height(c.x, c.y) + 0.5);
  }
  return c;
}

template <int Dim>
AnchorEntry* ShGraphCore<Dim>::acquire(const Key& key) {
  auto [it, inserted] = anchors_.try_emplace(key);
  if (inserted) {
    it->second.position = anchor_position(key);
    it->second.capture = capture_position(it->second.position);
  }
  ++it->second.refs;
  return &it->second;
}

template <int Dim>
void ShGraphCore<Dim>::forget(AnchorEntry* e) {
  if (e->anchor.has_coefficients()) by_age_.erase({e->anchor.creation_time(), e});
  if (e->anchor.fading()) std::erase(fading_, e);
}

template <int Dim>
void ShGraphCore<Dim>::set_coefficients(AnchorEntry* e, const Sh9Rgb& sh,
                                        const FinishedProbe& probe, const Sh9Rgb* fade_from,
                                        double fade_from_time) {
  CoefficientAnchor& a = e->anchor;
  if (a.has_coefficients()) by_age_.erase({a.creation_time(), e});
  if (!a.fading()) fading_.push_back(e);
  a.set_new(sh, probe.requested_time, probe.tag, fade_from, fade_from_time);
  by_age_.insert({a.creation_time(), e});
}

template <int Dim>
std::int32_t ShGraphCore<Dim>::alloc_block() {
  if (!free_blocks_.empty()) {
    const std::int32_t b = free_blocks_.back();
    free_blocks_.pop_back();
    return b;
  }
  const auto b = static_cast<std::int32_t>(nodes_.size());
  nodes_.resize(nodes_.size() + kChildren);
  return b;
}

template <int Dim>
void ShGraphCore<Dim>::init_child(std::int32_t parent, int c, std::int32_t slot) {
  Node n;
  n.depth = nodes_[parent].depth + 1;
  n.parent = parent;
  n.link.fill(-1);
  const std::int64_t step = 2 * half(n.depth);
  int rest = c;
  for (int a = 0; a < Dim; ++a) {
    n.key[a] = nodes_[parent].key[a] + static_cast<std::int64_t>(rest % 3 - 1) * step;
    rest /= 3;
  }
  n.anchor = acquire(n.key);
  nodes_[slot] = n;
}

template <int Dim>
void ShGraphCore<Dim>::link_children(std::int32_t parent) {
  const std::int32_t fc = nodes_[parent].first_child;
  int stride = 1;
  for (int a = 0; a < Dim; ++a) {
    for (int c = 0; c < kChildren; ++c) {
      const int o = (c / stride) % 3;  // 0, 1, 2 along axis a
      const std::int32_t me = fc + c;
      // +a side: a sibling, or the facing child of the parent's +a neighbour if it is expanded.
      std::int32_t other = -1;
      if (o < 2) {
        other = fc + c + stride;
      } else {
        const std::int32_t m = nodes_[parent].link[2 * a + 1];
        if (m >= 0 && nodes_[m].first_child >= 0) other = nodes_[m].first_child + c - 2 * stride;
      }
      if (other >= 0) {
        nodes_[me].link[2 * a + 1] = other;
        nodes_[other].link[2 * a] = me;
      }
      if (o == 0) {  // -a side across the parent boundary
        const std::int32_t m = nodes_[parent].link[2 * a];
        if (m >= 0 && nodes_[m].first_child >= 0) {
          const std::int32_t facing = nodes_[m].first_child + c + 2 * stride;
          nodes_[me].link[2 * a] = facing;
          nodes_[facing].link[2 * a + 1] = me;
        }
      }
    }
    stride *= 3;
  }
}

template <int Dim>
void ShGraphCore<Dim>::expand(std::int32_t i) {
  const std::int32_t block = alloc_block();  // may reallocate nodes_
  nodes_[i].first_child = block;
  for (int c = 0; c < kChildren; ++c) init_child(i, c, block + c);
  link_children(i);
}

template <int Dim>
void ShGraphCore<Dim>::release_node(std::int32_t i) {
  collapse(i);
  Node& n = nodes_[i];
  for (int d = 0; d < kLinks; ++d) {
    if (n.link[d] >= 0) nodes_[n.link[d]].link[d ^ 1] = -1;  // links go in pairs
    n.link[d] = -1;
  }
  auto it = anchors_.find(n.key);
  if (it != anchors_.end() && --it->second.refs == 0) {
    forget(&it->second);
    anchors_.erase(it);
  }
  n.anchor = nullptr;
  n.parent = -1;  // dead (slot 0, the root, is never released)
  n.children_with_coefficients = 0;
}

template <int Dim>
void ShGraphCore<Dim>::collapse(std::int32_t i) {
  const std::int32_t fc = nodes_[i].first_child;
  if (fc < 0) return;
  for (int c = 0; c < kChildren; ++c) release_node(fc + c);
  free_blocks_.push_back(fc);
  nodes_[i].first_child = -1;
  nodes_[i].children_with_coefficients = 0;
}

template <int Dim>
void ShGraphCore<Dim>::move_node(std::int32_t from, std::int32_t to) {
  nodes_[to] = nodes_[from];
  const Node& n = nodes_[to];
  if (n.first_child >= 0) {
    for (int c = 0; c < kChildren; ++c) nodes_[n.first_child + c].parent = to;
  }
  for (int d = 0; d < kLinks; ++d) {
    if (n.link[d] >= 0) nodes_[n.link[d]].link[d ^ 1] = to;
  }
}

template <int Dim>
bool ShGraphCore<Dim>::node_live(std::int32_t i) const {
  return i >= 0 && i < static_cast<std::int32_t>(nodes_.size()) &&
         (i == 0 || nodes_[i].parent >= 0);
}

template <int Dim>
bool ShGraphCore<Dim>::grow_towards(const Q& q) {
  // Keys stay within int64: half-sizes up to 3^38.
  if (dmax_ - nodes_[0].depth + 1 >= kMaxLevels - 1) return false;
  const std::int64_t hf = half(nodes_[0].depth);
  std::array<int, Dim> o{};
  int c_old = 0, stride = 1;
  Key key = nodes_[0].key;
  for (int a = 0; a < Dim; ++a) {
    const double rel = q[a] - static_cast<double>(key[a]);
    // D9: the old root sits on the side away from the target (centre where already inside).
    o[a] = rel < -static_cast<double>(hf) ? 1 : (rel >= static_cast<double>(hf) ? -1 : 0);
    key[a] -= static_cast<std::int64_t>(o[a]) * 2 * hf;
    c_old += (o[a] + 1) * stride;
    stride *= 3;
  }
  shrink_since_ = -1.0;
  const std::int32_t block = alloc_block();
  move_node(0, block + c_old);
  Node root;
  root.key = key;
  root.depth = nodes_[block + c_old].depth - 1;
  root.link.fill(-1);
  root.first_child = block;
  root.anchor = acquire(key);
  nodes_[0] = root;
  nodes_[block + c_old].parent = 0;
  for (int c = 0; c < kChildren; ++c) {
    if (c != c_old) init_child(0, c, block + c);
  }
  link_children(0);
  return true;
}

template <int Dim>
void ShGraphCore<Dim>::shrink_root(int child) {
  const std::int32_t fc = nodes_[0].first_child;
  const std::int32_t keep = fc + child;
  for (int c = 0; c < kChildren; ++c) {
    if (c != child) release_node(fc + c);
  }
  auto it = anchors_.find(nodes_[0].key);
  if (it != anchors_.end() && --it->second.refs == 0) {
    forget(&it->second);
    anchors_.erase(it);
  }
  move_node(keep, 0);
  nodes_[0].parent = -1;
  nodes_[keep].parent = -1;
  nodes_[keep].anchor = nullptr;
  nodes_[keep].first_child = -1;
  free_blocks_.push_back(fc);
}

template <int Dim>
std::int32_t ShGraphCore<Dim>::ensure_node(const Q& q, int depth) {
  if (!contains(0, q)) return -1;
  std::int32_t i = 0;
  while (nodes_[i].depth < depth) {
    if (nodes_[i].first_child < 0) {
      if (nodes_[i].depth >= dmax_) return i;
      expand(i);
    }
    i = nodes_[i].first_child + child_containing(i, q);
  }
  return i;
}

template <int Dim>
std::int32_t ShGraphCore<Dim>::neighbour(std::int32_t i, const std::array<int, Dim>& offset) const {
  // Walk the links axis by axis; try the other orders when an intermediate node is missing.
  static constexpr int kOrders3[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1},
                                         {0, 2, 1}, {1, 0, 2}, {2, 1, 0}};
  static constexpr int kOrders2[2][3] = {{0, 1, 0}, {1, 0, 0}};
  int nonzero = 0;
  for (int a = 0; a < Dim; ++a) nonzero += offset[a] != 0;
  const int tries = nonzero <= 1 ? 1 : (Dim == 3 ? 6 : 2);
  for (int t = 0; t < tries; ++t) {
    const int* order = Dim == 3 ? kOrders3[t] : kOrders2[t];
    std::int32_t j = i;
    for (int k = 0; k < Dim && j >= 0; ++k) {
      const int a = order[k];
      if (offset[a] != 0) j = nodes_[j].link[2 * a + (offset[a] > 0 ? 1 : 0)];
    }
    if (j >= 0) return j;
  }
  return -1;
}

template <int Dim>
void ShGraphCore<Dim>::neighbourhood_naive(std::int32_t i, Neighbourhood& out) const {
  std::array<int, Dim> o{};
  for (int n = 0; n < kChildren; ++n) {
    int rest = n;
    bool zero = true;
    for (int a = 0; a < Dim; ++a) {
      o[a] = rest % 3 - 1;
      rest /= 3;
      zero = zero && o[a] == 0;
    }
    out[static_cast<std::size_t>(n)] = zero ? i : neighbour(i, o);
  }
}

namespace {

// How ShGraphCore::neighbourhood() fills one cell of the 3^dim neighbourhood: from each cell
// with one fewer non-zero offset (one step back along an axis a where this cell's offset is
// non-zero) through that cell's link along a. Cells come in order of their number of non-zero
// offsets, so every source is filled before it is used.
struct NeighbourStep {
  std::int32_t cell = 0;
  std::int32_t count = 0;  // non-zero offsets = sources
  std::array<std::int32_t, 3> from{};
  std::array<std::int32_t, 3> link{};
};

template <int Dim>
struct NeighbourSteps {
  static constexpr int kCells = Dim == 3 ? 27 : 9;
  std::array<NeighbourStep, kCells - 1> step{};
  NeighbourSteps() {
    std::size_t k = 0;
    for (int nonzero = 1; nonzero <= Dim; ++nonzero) {
      for (int n = 0; n < kCells; ++n) {
        NeighbourStep st;
        st.cell = n;
        int rest = n, stride = 1;
        for (int a = 0; a < Dim; ++a, rest /= 3, stride *= 3) {
          const int o = rest % 3 - 1;
          if (o == 0) continue;
          st.from[static_cast<std::size_t>(st.count)] = n - o * stride;
          st.link[static_cast<std::size_t>(st.count)] = 2 * a + (o > 0 ? 1 : 0);
          ++st.count;
        }
        if (st.count == nonzero) step[k++] = st;
      }
    }
  }
};

template <int Dim>
const NeighbourSteps<Dim> kNeighbourSteps{};

}  // namespace

template <int Dim>
void ShGraphCore<Dim>::neighbourhood(std::int32_t i, Neighbourhood& out) const {
  // neighbour(i, o) for every offset at once. neighbour() walks one link per non-zero axis in
  // some axis order and returns the node where any order arrives (same-depth links are
  // geometric: every successful order ends at the same node), or -1. A cell is thus reachable
  // iff, for some non-zero axis a, the cell one step back along a is reachable and has a link
  // along a: filling cells by their number of non-zero offsets gives exactly neighbour()'s
  // answers with one link read per (cell, axis) instead of a walk per order.
  const Node* nodes = nodes_.data();
  out[static_cast<std::size_t>(kChildren / 2)] = i;
  for (const NeighbourStep& st : kNeighbourSteps<Dim>.step) {
    std::int32_t m = out[static_cast<std::size_t>(st.from[0])];
    std::int32_t r = m >= 0 ? nodes[m].link[static_cast<std::size_t>(st.link[0])] : -1;
    for (std::size_t t = 1; r < 0 && t < static_cast<std::size_t>(st.count); ++t) {
      m = out[static_cast<std::size_t>(st.from[t])];
      if (m >= 0) r = nodes[m].link[static_cast<std::size_t>(st.link[t])];
    }
    out[static_cast<std::size_t>(st.cell)] = r;
  }
}

template <int Dim>
std::int32_t ShGraphCore<Dim>::find_deepest(const Q& q, std::array<std::int32_t, kMaxLevels>& path,
                                            int* count) const {
  std::int32_t i = 0;
  int n = 0;
  path[n++] = 0;
  if (contains(0, q)) {
    while (nodes_[i].first_child >= 0 && n < kMaxLevels) {
      i = nodes_[i].first_child + child_containing(i, q);
      path[n++] = i;
    }
  }
  *count = n;
  return i;
}

template <int Dim>
double ShGraphCore<Dim>::root_size_now() const {
  return nodes_.empty() ? s_.root_size_m : cell_size(nodes_[0].depth);
}

template <int Dim>
double ShGraphCore<Dim>::cell_size(int depth) const {
  return 2.0 * static_cast<double>(half(depth)) * h_;
}

template <int Dim>
glm::dvec3 ShGraphCore<Dim>::node_centre(std::int32_t i) const {
  if constexpr (Dim == 2) return nodes_[i].anchor->position;
  glm::dvec3 p = origin_;
  for (int a = 0; a < Dim; ++a) p[a] += static_cast<double>(nodes_[i].key[a]) * h_;
  return p;
}

template <int Dim>
const CoefficientAnchor* ShGraphCore<Dim>::anchor_at(const glm::dvec3& p, int depth) const {
  if (nodes_.empty()) return nullptr;
  const Q q = to_q(p);
  if (!contains(0, q)) return nullptr;
  std::int32_t i = 0;
  while (nodes_[i].depth < depth && nodes_[i].first_child >= 0) {
    i = nodes_[i].first_child + child_containing(i, q);
  }
  if (nodes_[i].depth != depth) return nullptr;
  return &nodes_[i].anchor->anchor;
}

template <int Dim>
void ShGraphCore<Dim>::update_working_depth(const FrameContext& ctx) {
  const double fps = s_.fps_min > 0.0 ? s_.fps_min : (ctx.dt > 0.0 ? 1.0 / ctx.dt : 60.0);
  glm::dvec3 v = ctx.camera_velocity;
  if constexpr (Dim == 2) v.z = 0.0;  // the sheet only sees horizontal motion
  const double speed = glm::length(v);
  if (d_eff_ < 0 || ctx.camera_cut) {
    d_eff_ = depth_for_speed(speed, fps, ctx.faces_per_frame, s_);
    return;
  }
  // +-20 % speed hysteresis (D2): change level only once the speed has clearly left the band.
  const int lo = depth_for_speed(speed * 1.2, fps, ctx.faces_per_frame, s_);
  const int hi = depth_for_speed(speed / 1.2, fps, ctx.faces_per_frame, s_);
  d_eff_ = std::clamp(d_eff_, lo, hi);
}

template <int Dim>
std::vector<CaptureRequest> ShGraphCore<Dim>::plan(const FrameContext& ctx) {
  world_ = ctx.world;
  now_ = ctx.time;
  pending_.clear();  // anything neither started nor refused last frame never started
  update_working_depth(ctx);
  if (ctx.startable_captures <= 0) return {};
  const Focus focus = make_focus(ctx, s_.prediction);
  if (nodes_.empty()) {
    // The first root is centred on the camera; its min corner is the fixed key origin (D10).
    origin_ = focus.now;
    for (int a = 0; a < Dim; ++a) origin_[a] = focus.now[a] - 0.5 * s_.root_size_m;
    if constexpr (Dim == 2) origin_.z = 0.0;
    Node root;
    root.key.fill(pow3_[dmax_]);
    root.link.fill(-1);
    nodes_.push_back(root);
    nodes_[0].anchor = acquire(root.key);
  }
  const Q q_now = to_q(focus.now);
  const Q q_ahead = to_q(focus.ahead);
  while (!contains(0, q_now) && grow_towards(q_now)) {
  }
  while (!contains(0, q_ahead) && grow_towards(q_ahead)) {
  }

  struct Candidate {
    int tier;  // 0 missing near, 1 re-request near, 2 missing widened, 3 re-request widened
    int level;
    double score;  // distance to the focus, or capture time for re-requests (oldest first)
    Key key;
    glm::dvec3 capture;
    bool operator<(const Candidate& o) const {
      return std::tie(tier, level, score, key) < std::tie(o.tier, o.level, o.score, o.key);
    }
  };
  std::vector<Candidate> cands;
  std::set<Key> seen;
  const auto consider = [&](std::int32_t j, int near_tier, int level) {
    if (j < 0 || nodes_[j].depth != level) return;
    const AnchorEntry& e = *nodes_[j].anchor;
    if (e.anchor.in_flight() || !seen.insert(nodes_[j].key).second) return;
    glm::dvec3 c = e.position;
    if constexpr (Dim == 2) c.z = focus.now.z;  // horizontal distance on the sheet
    if (!e.anchor.has_coefficients()) {
      cands.push_back({near_tier, level, focus.distance(c), nodes_[j].key, e.capture});
    } else if (e.anchor.need_new()) {
      cands.push_back({near_tier + 1, 0, e.anchor.creation_time(), nodes_[j].key, e.capture});
    }
  };
  // Cells at `level` within Chebyshev radius r (exactly r when ring) of the focus segment.
  const auto region = [&](int level, int r, bool ring, int near_tier) {
    const double cell_q = 2.0 * static_cast<double>(half(level));
    double len = 0.0;
    for (int a = 0; a < Dim; ++a) len = std::max(len, std::abs(q_ahead[a] - q_now[a]));
    const int samples = 1 + static_cast<int>(std::ceil(len / cell_q));
    std::array<int, Dim> o{};
    const int side = 2 * r + 1;
    int cells = 1;
    for (int a = 0; a < Dim; ++a) cells *= side;
    for (int s = 0; s <= samples; ++s) {
      const double t = static_cast<double>(s) / samples;
      Q q;
      for (int a = 0; a < Dim; ++a) q[a] = q_now[a] + t * (q_ahead[a] - q_now[a]);
      const std::int32_t centre = ensure_node(q, level);
      if (centre < 0 || nodes_[centre].depth != level) continue;
      const Key ck = nodes_[centre].key;
      for (int n = 0; n < cells; ++n) {
        int rest = n, cheb = 0;
        for (int a = 0; a < Dim; ++a) {
          o[a] = rest % side - r;
          rest /= side;
          cheb = std::max(cheb, std::abs(o[a]));
        }
        if (ring && cheb != r) continue;
        Q p;
        for (int a = 0; a < Dim; ++a) p[a] = static_cast<double>(ck[a]) + o[a] * cell_q;
        if constexpr (Dim == 3) {
          if (s_.skip_underground && world_ != nullptr && world_->ground_height) {
            const double x = origin_.x + p[0] * h_, y = origin_.y + p[1] * h_;
            const double top = origin_.z + (p[2] + 0.5 * cell_q) * h_;
            if (top < world_->ground_height(x, y)) continue;  // the floor (L307)
          }
        }
        consider(ensure_node(p, level), near_tier, level);
      }
    }
  };
  const auto wanted = static_cast<std::size_t>(ctx.startable_captures);
  const int top = std::max(nodes_[0].depth, 0);
  // Coarse to fine, but only in the 3^Dim neighbourhood: sufficient resolution all around the
  // (predicted) camera at once, far nodes later (L566, L552).
  // At the normal root size and above only the focus cell itself: its neighbours are not part
  // of the normal graph, and capturing them would keep a grown root from ever shrinking (D9).
  for (int level = top; level <= d_eff_; ++level) region(level, level <= 0 ? 0 : 1, false, 0);
  // Then widen at the working depth (L420).
  for (int r = 2; d_eff_ > 0 && r <= s_.widen_cells && cands.size() < wanted; ++r) {
    region(d_eff_, r, true, 2);
  }
  std::sort(cands.begin(), cands.end());
  std::vector<CaptureRequest> out;
  for (const auto& c : cands) {
    if (out.size() >= wanted) break;
    const std::uint64_t tag = next_tag_++;
    pending_[tag] = {c.key, ctx.time};
    out.push_back({c.capture, tag});
  }
  return out;
}

template <int Dim>
void ShGraphCore<Dim>::started(std::uint64_t tag) {
  auto it = pending_.find(tag);
  if (it == pending_.end()) return;
  auto a = anchors_.find(it->second.key);
  if (a != anchors_.end()) a->second.anchor.prepare_for_new();
  in_flight_[tag] = it->second;
  pending_.erase(it);
}

template <int Dim>
void ShGraphCore<Dim>::refused(std::uint64_t tag) {
  pending_.erase(tag);
}

template <int Dim>
void ShGraphCore<Dim>::deliver(const FinishedProbe& probe) {
  auto it = in_flight_.find(probe.tag);
  if (it == in_flight_.end()) return;
  const Key key = it->second.key;
  in_flight_.erase(it);
  auto a = anchors_.find(key);
  if (a == anchors_.end()) return;  // its branch was removed meanwhile
  CoefficientAnchor& anchor = a->second.anchor;
  const Sh9Rgb sh = s_.format.store(probe.sh);
  if (!anchor.has_coefficients() && s_.fade_from_lookup && s_.timing.fade_s > 0.0) {
    // D8: fade from what a lookup showed here just before, so the new set does not pop.
    const LookupResult before = lookup(a->second.position);
    if (before.contributor_count > 0) {
      set_coefficients(&a->second, sh, probe, &before.sh, before.data_time);
      return;
    }
  }
  set_coefficients(&a->second, sh, probe, nullptr, 0.0);
}

template <int Dim>
bool ShGraphCore<Dim>::protected_node(std::int32_t i, const Focus& focus) const {
  glm::dvec3 c = node_centre(i);
  Focus f = focus;
  if constexpr (Dim == 2) {
    c.z = 0.0;
    f.now.z = f.ahead.z = 0.0;
  }
  // Children of cells next to the focus are about to be wanted again: keep them.
  return f.distance(c) < 2.0 * cell_size(nodes_[i].depth);
}

template <int Dim>
std::uint32_t ShGraphCore<Dim>::refresh_masks(std::int32_t i, const Focus& focus, bool* in_flight) {
  std::uint32_t mask = 0;
  bool flight = false;
  bool own_data = false;  // data in a child other than through the shared centre anchor
  const std::int32_t fc = nodes_[i].first_child;
  if (fc >= 0) {
    for (int c = 0; c < kChildren; ++c) {
      bool cf = false;
      std::uint32_t m = 0;
      if (naive_ || nodes_[fc + c].first_child >= 0) {
        m = refresh_masks(fc + c, focus, &cf);
      } else {
        nodes_[fc + c].children_with_coefficients = 0;  // a leaf: what the call would do
      }
      const bool has = nodes_[fc + c].anchor->anchor.has_coefficients();
      if (has || m != 0) mask |= 1u << c;
      if (m != 0 || (has && c != kCentreChild)) own_data = true;
      flight = flight || cf || nodes_[fc + c].anchor->anchor.in_flight();
    }
    // Prune: no child holds coefficients of its own (the centre's are the parent's, which
    // keeps them), nothing is being captured below, and the camera is not about to need it.
    if (!own_data && !flight && !protected_node(i, focus)) {
      collapse(i);
      mask = 0;
    }
  }
  nodes_[i].children_with_coefficients = mask;
  *in_flight = flight;
  return mask;
}

template <int Dim>
void ShGraphCore<Dim>::update(const FrameContext& ctx) {
  world_ = ctx.world;
  now_ = ctx.time;
  AnchorTiming timing = s_.timing;
  const double latency = ctx.capture_latency_s();
  timing.margin_s = 2.0 * (std::isfinite(latency) ? latency : 0.0) + 1.0;  // D7
  // Every anchor's update(), visiting only those it can change: anchors mid-fade, and anchors
  // whose set is old enough to expire or to ask for renewal now. For any other anchor with a
  // set, age <= lifetime - max(margin now, margin before) - 1 s: not expired, and its renewal
  // flag is false now and was false after the previous update (its age was smaller then), so
  // update() would leave it as it is. Anchors without a set and not fading: update() is a no-op.
  // The anchors are independent, so the order of the visits does not matter.
  if (naive_) {
    for (auto& [key, e] : anchors_) e.anchor.update(now_, timing);
    for (auto it = by_age_.begin(); it != by_age_.end();) {
      it = it->second->anchor.has_coefficients() ? std::next(it) : by_age_.erase(it);
    }
  } else {
    for (AnchorEntry* e : fading_) e->anchor.update(now_, timing);
    std::vector<AnchorEntry*> faded = fading_;
    std::sort(faded.begin(), faded.end());
    const double renew_age = s_.timing.lifetime_s - std::max(timing.margin_s, margin_prev_s_) - 1.0;
    for (auto it = by_age_.begin(); it != by_age_.end() && now_ - it->first > renew_age;) {
      AnchorEntry* e = it->second;
      if (!std::binary_search(faded.begin(), faded.end(), e)) e->anchor.update(now_, timing);
      it = e->anchor.has_coefficients() ? std::next(it) : by_age_.erase(it);
    }
  }
  margin_prev_s_ = timing.margin_s;
  std::erase_if(fading_, [](const AnchorEntry* e) { return !e->anchor.fading(); });
  // A capture that never came back (budget gone) must not block its anchor for ever.
  for (auto it = in_flight_.begin(); it != in_flight_.end();) {
    if (now_ - it->second.requested_time > s_.timing.lifetime_s) {
      auto a = anchors_.find(it->second.key);
      if (a != anchors_.end()) a->second.anchor.cancel_request();
      it = in_flight_.erase(it);
    } else {
      ++it;
    }
  }
  if (nodes_.empty()) return;
  const Focus focus = make_focus(ctx, s_.prediction);
  bool flight = false;
  refresh_masks(0, focus, &flight);
  // D9 shrink: a grown root goes once at most one child holds coefficients (for
  // shrink_hold_s), keeping that child, provided the camera is in it (else it would regrow).
  while (nodes_[0].depth < 0 && nodes_[0].first_child >= 0) {
    const std::uint32_t mask = nodes_[0].children_with_coefficients;
    const int child = child_containing(0, to_q(focus.now));
    if (std::popcount(mask) > 1 || (mask != 0 && mask != (1u << child)) ||
        !contains(0, to_q(focus.now))) {
      shrink_since_ = -1.0;
      break;
    }
    if (shrink_since_ < 0.0) shrink_since_ = now_;
    if (now_ - shrink_since_ < s_.shrink_hold_s) break;
    shrink_root(child);
  }
}

template <int Dim>
LookupResult ShGraphCore<Dim>::lookup(const glm::dvec3& p) const {
  LookupResult r;  // filled in place: one named result, so no copy on return
  if (!lookup_into(p, r)) r = default_ambient_lookup();
  return r;
}

template <int Dim>
bool ShGraphCore<Dim>::lookup_into(const glm::dvec3& p, LookupResult& r) const {
  if (nodes_.empty()) return false;
  const Q q = to_q(p);
  const bool outside = !contains(0, q);
  std::array<std::int32_t, kMaxLevels> path;
  int count = 0;
  find_deepest(q, path, &count);

  constexpr int kOctants = 1 << Dim;
  struct Best {
    const AnchorEntry* e = nullptr;
    double d2 = kInf;
  };
  std::array<Best, kOctants> best{}, chosen{};
  int chosen_depth = 0;
  bool have = false;
  std::array<std::int32_t, kChildren> cells{};
  for (int k = count - 1; k >= 0; --k) {
    const std::int32_t i = path[k];
    best.fill(Best{});
    std::uint32_t covered = 0;
    // D5: the node and its 3^Dim - 1 same-depth neighbours, reached through the links.
    if (naive_) {
      neighbourhood_naive(i, cells);
    } else {
      neighbourhood(i, cells);
    }
    if (naive_) {
      for (int n = 0; n < kChildren; ++n) {
        const std::int32_t j = cells[static_cast<std::size_t>(n)];
        if (j < 0) continue;
        const AnchorEntry* e = nodes_[j].anchor;
        if (!e->anchor.has_coefficients()) continue;
        double d2 = 0.0;
        int oct = 0;
        for (int a = 0; a < Dim; ++a) {
          const double dq = static_cast<double>(nodes_[j].key[a]) - q[a];
          d2 += dq * dq;
          if (dq >= 0.0) oct |= 1 << a;
        }
        covered |= 1u << oct;
        if (d2 < best[oct].d2) best[oct] = {e, d2};
      }
    } else {
      const Node* nodes = nodes_.data();
      for (std::size_t n = 0; n < static_cast<std::size_t>(kChildren); ++n) {
        const std::int32_t j = cells[n];
        if (j < 0) continue;
        const Node& nd = nodes[j];
        const AnchorEntry* e = nd.anchor;
        if (!e->anchor.has_coefficients()) continue;
        double d2 = 0.0;
        int oct = 0;
        for (int a = 0; a < Dim; ++a) {
          const double dq = static_cast<double>(nd.key[a]) - q[a];
          d2 += dq * dq;
          oct |= (dq >= 0.0 ? 1 : 0) << a;
        }
        covered |= 1u << oct;
        Best& b = best[static_cast<std::size_t>(oct)];
        if (d2 < b.d2) b = {e, d2};
      }
    }
    if (covered == 0) continue;
    if (!have) {
      chosen = best;
      chosen_depth = nodes_[i].depth;
      have = true;
    }
    if (s_.level == LevelRule::first) break;
    if (covered == (1u << kOctants) - 1) {
      chosen = best;
      chosen_depth = nodes_[i].depth;
      break;
    }
  }
  if (!have) return false;
  const double cell = cell_size(chosen_depth);
  const double eps_q = 1e-3 * cell / h_;
  std::array<double, kOctants> w{};
  double sum = 0.0;
  for (int k = 0; k < kOctants; ++k) {
    if (!chosen[k].e) continue;
    const double d = std::sqrt(chosen[k].d2);
    if (d < eps_q) {  // an exact hit is that set alone (D4)
      w.fill(0.0);
      w[k] = 1.0;
      sum = 1.0;
      break;
    }
    if (s_.weights == WeightMode::compact) {
      w[k] = std::max(0.0, 1.0 - d * h_ / (2.0 * cell));
    } else {
      w[k] = 1.0 / d;
    }
    sum += w[k];
  }
  if (sum <= 0.0) {  // compact support left nothing: fall back to inverse distance
    for (int k = 0; k < kOctants; ++k) {
      if (chosen[k].e) sum += (w[k] = 1.0 / std::sqrt(chosen[k].d2));
    }
  }
  double data_time = 0.0;
  // The fast path sums the 27 floats of each set as one flat array (vectorised): the same
  // products and sums, element by element, as the naive path's operators.
  static_assert(sizeof(Sh9Rgb) == kShCount * 3 * sizeof(float));
  std::array<float, kShCount * 3> acc{};
  for (int k = 0; k < kOctants; ++k) {
    if (!chosen[k].e || w[k] <= 0.0) continue;
    const double wk = w[k] / sum;
    const CoefficientAnchor& a = chosen[k].e->anchor;
    if (naive_) {
      r.sh += a.active() * static_cast<float>(wk);
    } else {
      const auto wf = static_cast<float>(wk);
      // Straight from the set's bytes (27 floats), no copy of it on the stack.
      const auto* bytes = reinterpret_cast<const unsigned char*>(&a.active());
      for (std::size_t c = 0; c < acc.size(); ++c) {
        float v;
        std::memcpy(&v, bytes + c * sizeof(float), sizeof v);
        acc[c] += v * wf;
      }
    }
    r.contributors[static_cast<std::size_t>(r.contributor_count++)] = {a.tag(),
                                                                       static_cast<float>(wk)};
    data_time += wk * a.data_time();
  }
  if (!naive_) {
    for (std::size_t c = 0; c < r.sh.c.size(); ++c) {
      r.sh.c[c] = Rgb(acc[3 * c], acc[3 * c + 1], acc[3 * c + 2]);
    }
  }
  r.data_time = data_time;
  r.spacing_m = cell;
  r.fell_back = outside;  // outside the graph: the root's answer is only a coarse default
  return true;
}

template <int Dim>
PlannerStats ShGraphCore<Dim>::stats() const {
  PlannerStats s;
  if (naive_) {
    for (const auto& [key, e] : anchors_) s.live_probes += e.anchor.has_coefficients() ? 1 : 0;
  } else {
    s.live_probes = static_cast<std::int64_t>(by_age_.size());  // the anchors holding a set
  }
  s.nodes = static_cast<std::int64_t>(nodes_.size() - free_blocks_.size() * kChildren);
  // Sets: Active + New per anchor, as the format stores them. Structure: the anchor's
  // bookkeeping (its struct minus the two float sets), the key and a map node each; the node
  // pool as allocated; the free list; the capture tag maps.
  const std::size_t per_anchor = 2 * s_.format.bytes_per_set() +
                                 (sizeof(AnchorEntry) - 2 * sizeof(Sh9Rgb)) + sizeof(Key) +
                                 kMapNodeOverhead;
  const std::size_t per_tag =
      sizeof(typename std::map<std::uint64_t, InFlight>::value_type) + kMapNodeOverhead;
  s.bytes =
      static_cast<std::int64_t>(anchors_.size() * per_anchor + nodes_.capacity() * sizeof(Node) +
                                free_blocks_.capacity() * sizeof(std::int32_t) +
                                (pending_.size() + in_flight_.size()) * per_tag);
  return s;
}

template <int Dim>
void ShGraphCore<Dim>::describe_nodes(std::vector<ProbeNodeView>& out) const {
  if (nodes_.empty()) return;
  for (std::int32_t i = 0; i < static_cast<std::int32_t>(nodes_.size()); ++i) {
    if (!node_live(i)) continue;
    const Node& n = nodes_[i];
    const CoefficientAnchor& a = n.anchor->anchor;
    ProbeNodeView v;
    v.centre = node_centre(i);
    const double hf = 0.5 * cell_size(n.depth);
    v.half_extent = glm::dvec3(hf, hf, Dim == 3 ? hf : 0.0);
    v.depth = n.depth - nodes_[0].depth;
    v.has_data = a.has_coefficients();
    v.in_flight = a.in_flight();
    v.age_s = a.has_coefficients() ? now_ - a.creation_time() : 0.0;
    if (v.has_data) v.sh = a.active();
    out.push_back(v);
  }
}

template class ShGraphCore<2>;
template class ShGraphCore<3>;

}  // namespace ambisim
