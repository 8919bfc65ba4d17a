#pragma once
// Integer lattice keys for the octree (thesis 8.4.1, decision D10). Corners are identified by
// an int64 triple on the finest lattice (spacing cell_m, from the fixed world origin), nodes by
// (depth, int64 index on that depth's lattice). Positions are derived from keys, never keys
// from computed positions, so two nodes sharing a corner always share its key: the thesis'
// float-key bug (L558: rounding gave one corner two positions) cannot happen, at any distance
// from the origin.
#include <algorithm>
#include <array>
#include <cmath>
#include <compare>
#include <cstdint>

#include <glm/vec3.hpp>

namespace ambisim {

struct LatticeKey {
  std::int64_t x = 0, y = 0, z = 0;
  friend auto operator<=>(const LatticeKey&, const LatticeKey&) = default;
};

// A node: its depth (0 = root) and its index on the depth's lattice, relative to the root.
struct NodeKey {
  int depth = 0;
  std::int64_t x = 0, y = 0, z = 0;
  friend auto operator<=>(const NodeKey&, const NodeKey&) = default;
};

// A cube root of 2^max_depth finest cells per side whose minimum corner is the lattice point
// `min_key`. Corner/child index i: bit 0 = +x, bit 1 = +y, bit 2 = +z.
class OctreeLattice {
 public:
  static constexpr int kMaxDepth = 48;  // 2^48 cells: far beyond any world, still int64-safe

  OctreeLattice() = default;
  OctreeLattice(LatticeKey min_key, int max_depth, double cell_m)
      : min_(min_key), depth_(std::clamp(max_depth, 0, kMaxDepth)), cell_(cell_m) {}

  // The smallest root (a power-of-two number of cells) containing the box [lo, hi].
  static OctreeLattice covering(const glm::dvec3& lo, const glm::dvec3& hi, double cell_m) {
    const LatticeKey a{floor_cell(lo.x, cell_m), floor_cell(lo.y, cell_m),
                       floor_cell(lo.z, cell_m)};
    const std::int64_t ext = std::max({ceil_cell(hi.x, cell_m) - a.x, ceil_cell(hi.y, cell_m) - a.y,
                                       ceil_cell(hi.z, cell_m) - a.z, std::int64_t{1}});
    int d = 0;
    while (d < kMaxDepth && (std::int64_t{1} << d) < ext) ++d;
    return OctreeLattice(a, d, cell_m);
  }

  int max_depth() const { return depth_; }
  double cell_m() const { return cell_; }
  LatticeKey min_key() const { return min_; }
  // Edge length of a depth-d node, in finest cells and in metres.
  std::int64_t cells(int depth) const { return std::int64_t{1} << (depth_ - depth); }
  double size_m(int depth) const { return static_cast<double>(cells(depth)) * cell_; }

  glm::dvec3 position(const LatticeKey& k) const {
    return {static_cast<double>(k.x) * cell_, static_cast<double>(k.y) * cell_,
            static_cast<double>(k.z) * cell_};
  }
  // The nearest lattice point (for tests and diagnostics; the planner never keys by position).
  LatticeKey key_of(const glm::dvec3& p) const {
    return {std::llround(p.x / cell_), std::llround(p.y / cell_), std::llround(p.z / cell_)};
  }

  // Inside the root's closed box.
  bool contains(const glm::dvec3& p) const {
    const std::int64_t n = cells(0);
    const auto in = [&](double v, std::int64_t lo) {
      const double t = v / cell_ - static_cast<double>(lo);
      return t >= 0.0 && t <= static_cast<double>(n);
    };
    return in(p.x, min_.x) && in(p.y, min_.y) && in(p.z, min_.z);
  }
  // The depth-d node containing p (p inside the root; the max faces belong to the last cell).
  NodeKey node_at(const glm::dvec3& p, int depth) const {
    const std::int64_t n = cells(0);
    const auto cell = [&](double v, std::int64_t lo) {
      return std::clamp(floor_cell(v, cell_) - lo, std::int64_t{0}, n - 1) >> (depth_ - depth);
    };
    return {depth, cell(p.x, min_.x), cell(p.y, min_.y), cell(p.z, min_.z)};
  }

  static NodeKey root() { return {}; }
  static NodeKey child(const NodeKey& n, int i) {
    return {n.depth + 1, 2 * n.x + (i & 1), 2 * n.y + ((i >> 1) & 1), 2 * n.z + ((i >> 2) & 1)};
  }
  static NodeKey parent(const NodeKey& n) { return {n.depth - 1, n.x >> 1, n.y >> 1, n.z >> 1}; }
  // The depth-d ancestor of n (d <= n.depth).
  static NodeKey ancestor(const NodeKey& n, int d) {
    const int s = n.depth - d;
    return {d, n.x >> s, n.y >> s, n.z >> s};
  }
  static bool is_ancestor_or_self(const NodeKey& a, const NodeKey& n) {
    return a.depth <= n.depth && ancestor(n, a.depth) == a;
  }
  // Depth of the deepest common ancestor (0 = only the root in common).
  static int common_ancestor_depth(const NodeKey& a, const NodeKey& b) {
    int d = std::min(a.depth, b.depth);
    while (d > 0 && ancestor(a, d) != ancestor(b, d)) --d;
    return d;
  }

  LatticeKey corner(const NodeKey& n, int i) const {
    const std::int64_t c = cells(n.depth);
    return {min_.x + (n.x + (i & 1)) * c, min_.y + (n.y + ((i >> 1) & 1)) * c,
            min_.z + (n.z + ((i >> 2) & 1)) * c};
  }
  glm::dvec3 min_position(const NodeKey& n) const { return position(corner(n, 0)); }
  glm::dvec3 centre(const NodeKey& n) const {
    return (position(corner(n, 0)) + position(corner(n, 7))) * 0.5;
  }
  // The 27 lattice points of a node's split (index a + 3 b + 9 c, a/b/c in {0, 1, 2} per axis):
  // its 8 corners plus the 19 points the split adds.
  std::array<LatticeKey, 27> split_points(const NodeKey& n) const {
    std::array<LatticeKey, 27> out{};
    const std::int64_t h = cells(n.depth) / 2;
    const LatticeKey m = corner(n, 0);
    for (int i = 0; i < 27; ++i) {
      out[static_cast<std::size_t>(i)] = {m.x + (i % 3) * h, m.y + (i / 3 % 3) * h,
                                          m.z + (i / 9) * h};
    }
    return out;
  }
  // The coarsest depth whose lattice holds k (0 for a root corner); k inside the root.
  int level_of(const LatticeKey& k) const {
    for (int d = 0; d < depth_; ++d) {
      const std::int64_t c = cells(d);
      if ((k.x - min_.x) % c == 0 && (k.y - min_.y) % c == 0 && (k.z - min_.z) % c == 0) return d;
    }
    return depth_;
  }

 private:
  static std::int64_t floor_cell(double v, double cell) {
    return static_cast<std::int64_t>(std::floor(v / cell));
  }
  static std::int64_t ceil_cell(double v, double cell) {
    return static_cast<std::int64_t>(std::ceil(v / cell));
  }

  LatticeKey min_{};
  int depth_ = 0;
  double cell_ = 1.0;
};

}  // namespace ambisim
