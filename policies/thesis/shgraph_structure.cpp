// SHGraph's structure: cells split 3 per axis, their same-depth links in pairs, root growth and
// shrink (D9), and the walks that planning and lookups use.
#include "policies/thesis/shgraph_core.h"

#include <algorithm>
#include <array>
#include <cstdint>

#include "policies/core/solid_clearance.h"

namespace ambisim {

template <int Dim>
ShGraphCore<Dim>::ShGraphCore(const ShGraphSettings& s)
    : s_(s), clock_(s.refresh_by_rate, s.timing.lifetime_s, s.refresh_tolerance) {
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
  if constexpr (Dim == 3) return anchor_point(key, origin_.z + static_cast<double>(key[2]) * h_);
  glm::dvec3 p = anchor_point(key, 0.0);
  p.z = ground_at(p.x, p.y) + s_.sheet_height_m;
  return p;
}

template <int Dim>
glm::dvec3 ShGraphCore<Dim>::anchor_point(const Key& key, double z) const {
  return {origin_.x + static_cast<double>(key[0]) * h_,
          origin_.y + static_cast<double>(key[1]) * h_, z};
}

template <int Dim>
glm::dvec3 ShGraphCore<Dim>::capture_position(const glm::dvec3& nominal) const {
  // Out of terrain and canopy alike (L318): a cube map rendered inside a crown sees its
  // backfaces just as one inside a hill. Whether the move is small enough for the cell to keep
  // the set is decided where the cell's size is known (plan()).
  return above_solids(world_, nominal, s_.lift_m);
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
  n.anchor = share_existing(n.key);  // the centre child of a considered cell shares its anchor
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
  release_key(i);
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
  root.anchor = share_existing(key);
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
  // The root gives up its key; its other children went before it, so only a kept centre child
  // still holds the key.
  if (nodes_[0].anchor != nullptr) {
    if (--nodes_[0].anchor->refs == 0) {
      forget(nodes_[0].anchor);
      anchors_.erase(nodes_[0].key);
    }
  } else if (child != kCentreChild) {
    ++forgotten_;
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
  if constexpr (Dim == 2) {
    // The sheet's height there: the anchor's, or what the anchor would be made with.
    return nodes_[i].anchor != nullptr ? anchor_point(nodes_[i].key, nodes_[i].anchor->position_z)
                                       : anchor_position(nodes_[i].key);
  }
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
  if (nodes_[i].depth != depth || nodes_[i].anchor == nullptr) return nullptr;
  return &nodes_[i].anchor->anchor;
}

// The members defined here, for both dimensions: the class template is declared extern in
// the header, and each concern's file instantiates its own members.
template ShGraphCore<2>::ShGraphCore(const ShGraphSettings&);
template ShGraphCore<2>::Q ShGraphCore<2>::to_q(const glm::dvec3&) const;
template bool ShGraphCore<2>::contains(std::int32_t, const Q&) const;
template int ShGraphCore<2>::child_containing(std::int32_t, const Q&) const;
template double ShGraphCore<2>::ground_at(double, double) const;
template glm::dvec3 ShGraphCore<2>::anchor_position(const Key&) const;
template glm::dvec3 ShGraphCore<2>::capture_position(const glm::dvec3&) const;
template glm::dvec3 ShGraphCore<2>::anchor_point(const Key&, double) const;
template std::int32_t ShGraphCore<2>::alloc_block();
template void ShGraphCore<2>::init_child(std::int32_t, int, std::int32_t);
template void ShGraphCore<2>::link_children(std::int32_t);
template void ShGraphCore<2>::expand(std::int32_t);
template void ShGraphCore<2>::release_node(std::int32_t);
template void ShGraphCore<2>::collapse(std::int32_t);
template void ShGraphCore<2>::move_node(std::int32_t, std::int32_t);
template bool ShGraphCore<2>::node_live(std::int32_t) const;
template bool ShGraphCore<2>::grow_towards(const Q&);
template void ShGraphCore<2>::shrink_root(int);
template std::int32_t ShGraphCore<2>::ensure_node(const Q&, int);
template std::int32_t ShGraphCore<2>::neighbour(std::int32_t, const std::array<int, 2>&) const;
template void ShGraphCore<2>::neighbourhood_naive(std::int32_t, Neighbourhood&) const;
template void ShGraphCore<2>::neighbourhood(std::int32_t, Neighbourhood&) const;
template std::int32_t ShGraphCore<2>::find_deepest(const Q&, std::array<std::int32_t, kMaxLevels>&,
                                                   int*) const;
template double ShGraphCore<2>::root_size_now() const;
template double ShGraphCore<2>::cell_size(int) const;
template glm::dvec3 ShGraphCore<2>::node_centre(std::int32_t) const;
template const CoefficientAnchor* ShGraphCore<2>::anchor_at(const glm::dvec3&, int) const;
template ShGraphCore<3>::ShGraphCore(const ShGraphSettings&);
template ShGraphCore<3>::Q ShGraphCore<3>::to_q(const glm::dvec3&) const;
template bool ShGraphCore<3>::contains(std::int32_t, const Q&) const;
template int ShGraphCore<3>::child_containing(std::int32_t, const Q&) const;
template double ShGraphCore<3>::ground_at(double, double) const;
template glm::dvec3 ShGraphCore<3>::anchor_position(const Key&) const;
template glm::dvec3 ShGraphCore<3>::capture_position(const glm::dvec3&) const;
template glm::dvec3 ShGraphCore<3>::anchor_point(const Key&, double) const;
template std::int32_t ShGraphCore<3>::alloc_block();
template void ShGraphCore<3>::init_child(std::int32_t, int, std::int32_t);
template void ShGraphCore<3>::link_children(std::int32_t);
template void ShGraphCore<3>::expand(std::int32_t);
template void ShGraphCore<3>::release_node(std::int32_t);
template void ShGraphCore<3>::collapse(std::int32_t);
template void ShGraphCore<3>::move_node(std::int32_t, std::int32_t);
template bool ShGraphCore<3>::node_live(std::int32_t) const;
template bool ShGraphCore<3>::grow_towards(const Q&);
template void ShGraphCore<3>::shrink_root(int);
template std::int32_t ShGraphCore<3>::ensure_node(const Q&, int);
template std::int32_t ShGraphCore<3>::neighbour(std::int32_t, const std::array<int, 3>&) const;
template void ShGraphCore<3>::neighbourhood_naive(std::int32_t, Neighbourhood&) const;
template void ShGraphCore<3>::neighbourhood(std::int32_t, Neighbourhood&) const;
template std::int32_t ShGraphCore<3>::find_deepest(const Q&, std::array<std::int32_t, kMaxLevels>&,
                                                   int*) const;
template double ShGraphCore<3>::root_size_now() const;
template double ShGraphCore<3>::cell_size(int) const;
template glm::dvec3 ShGraphCore<3>::node_centre(std::int32_t) const;
template const CoefficientAnchor* ShGraphCore<3>::anchor_at(const glm::dvec3&, int) const;

}  // namespace ambisim
