#pragma once
// The ambisim planner's far field: what a lookup mixes in where the probes' bumps weigh little
// (in a bump's outer half and beyond every bump), continuous in space and in time, at a cost
// per lookup that does not grow with the number of probes.
//
// A pyramid of sparse grids filled by pull-push, the hole filling of Gortler et al., "The
// Lumigraph" (SIGGRAPH 1996). Each probe adds its presence w, w x its coefficients and w x its
// data time to the level-0 cell that holds it (kBaseCellM cells); a cell of level k + 1 sums its
// 8 children. A point reads level k by trilinear interpolation between the 8 cell centres
// around it, of the sums N_k and of the weights W_k apart, and the levels are blended from the
// finest:
//   F(p) = sum_k (prod_{j<k} (1 - a_j)) a_k N_k / W_k,   a_k = min(1, W_k / kConfidence),
// closed by the mean over every probe (weighted by presence) for what the levels leave.
//
// Why it does not pop: every term is continuous in the point (trilinear weights; where W_k <
// kConfidence, a_k N_k / W_k = N_k / kConfidence, which goes to 0 with W_k) and in the probes'
// presences and values, which the planner fades. A cell is fixed by a probe's position, which
// never moves, so nothing jumps when probes arrive or leave: they fade in and out of their
// cell's sums. (An earlier far field summed probes into coarse cells only once they were
// steady: each jumped from its own term to its cell's, and viewed pops rose ninefold.)
//
// A lookup reads 8 cells per level, most of them empty away from the probes; a one-hash filter
// per level (CellFilter) answers those finds without probing the table (far field 154 -> 111 ns
// per lookup at BM_Lookup/ambisim/10000).
//
// Input ranges: positions and points finite. Coordinates are clamped to +-2^20 level-0 cells
// (8,000 km), which only makes a far point's cells empty: it gets the mean of every probe.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/common.hpp>
#include <glm/vec3.hpp>

#include "policies/ambisim/cell_filter.h"
#include "policies/ambisim/cell_key.h"
#include "sim/sh/sh9.h"

namespace ambisim {

class FarField {
 public:
  // A power of two, so that coarser levels are exact shifts. 16 m: about four times the reach of
  // a probe's bump at the default 3 m spacing, and few enough cells to hold (8 m cost 100 B per
  // probe in bench_planners' fill, 16 m about 35).
  static constexpr double kBaseCellM = 16.0;
  static constexpr int kLevels = 9;  // cells of 16 m to 4 km
  // The interpolated presence at which a level answers alone (one fully present probe's worth).
  static constexpr double kConfidence = 1.0;

  // What a probe adds, or what a cell sums: w x coefficients, w, w x data time (116 bytes:
  // floats hold sums of up to 1e5 presences and times to a few parts in 1e7).
  struct Sums {
    Sh9Rgb sh;
    float weight = 0.0f;
    float time = 0.0f;
  };
  struct Answer {
    Sh9Rgb sh;
    double data_time = 0.0;
    double cell_m = 0.0;  // the cell of the finest level that contributed (its resolution)
  };

  // The cells of every level over positions[0, n): slots 0..n-1.
  void build(std::span<const glm::dvec3> positions);
  // Adds slot size() at position (its sums zero until the next fill, which includes it: a
  // refill_marked() redoes its cell and that cell's ancestors).
  void append(const glm::dvec3& position);
  std::size_t size() const { return cell_of_slot_.size(); }
  // Every slot's sums, from add(slot, sums) (which adds that slot's to sums), then up the levels.
  template <class AddSlot>
  void fill(AddSlot&& add);
  // The same sums, bit for bit, recomputing only the cells that hold a slot marked since the
  // last fill and their ancestors: a cell sums its slots in slot order and a parent its
  // children in cell order, as fill() does, so an unmarked cell keeps what fill() would give it
  // again. The caller marks every slot whose add() may have changed (append() marks its own).
  // After build() it is a full fill().
  void mark(std::size_t slot);
  template <class AddSlot>
  void refill_marked(AddSlot&& add);
  // What a batch of evaluate() calls shares (the planner's lookup_many: a frame's receivers
  // cluster, so most read the cell blocks of their neighbours): for each block of 8 corners read
  // so far, which corners hold a cell. A block read again costs one probe of the memo instead of
  // 8 filter tests and finds; the corners are then summed in the same order, so the answer is
  // the same bit for bit. Valid until the far field is appended to or built again.
  class CornerMemo {
   public:
    // Sized for a batch of `points` evaluations (small batches do not pay for a large memo).
    explicit CornerMemo(std::size_t points) {
      while (blocks_ < points && blocks_ < 1024) blocks_ *= 2;
    }

   private:
    friend class FarField;
    struct Block {
      std::uint64_t key = kEmptyCellKey;  // the block's first corner (c0), packed
      std::int32_t cell[8];               // the occupied corners' cells, in corner order
      std::uint8_t corner[8];             // and their corner numbers n (dx + 2 dy + 4 dz)
      std::uint8_t count = 0;
    };
    // Direct-mapped per level, made at a level's first read: up to 1,024 blocks, which hold a
    // frame's receivers within a few hundred metres (a 50 m disc reads about 150 of 16 m).
    std::size_t blocks_ = 16;
    std::vector<Block> levels_[kLevels];
  };
  // F at p; false when no slot has weight. With a memo, the same F from fewer finds.
  bool evaluate(const glm::dvec3& p, Answer& out, CornerMemo* memo = nullptr) const;
  // The same F from the slots themselves: each level's sums around p by a scan of every slot
  // (add as for fill). The reference evaluate() is tested against.
  template <class AddSlot>
  static bool evaluate_reference(const glm::dvec3& p, std::span<const glm::dvec3> positions,
                                 AddSlot&& add, Answer& out);
  std::size_t bytes() const;

 private:
  struct Level {
    std::vector<std::uint64_t> keys;  // open addressing, capacity a power of two
    std::vector<std::int32_t> index;  // the cell of each key's slot (-1: empty)
    CellFilter filter;                // over the keys, sized for the table's capacity
    std::vector<Sums> cells;          // in insertion order
    std::vector<std::uint64_t> cell_keys;
    std::vector<std::int32_t> parent;  // each cell's cell in the next level (-1: last level)
    // refill_marked(): the members of each cell (level 0: slots; above: the children's cells),
    // in order, as ranges of one array (first[c], first[c + 1]); and which cells to redo.
    std::vector<std::int32_t> first;
    std::vector<std::int32_t> members;
    std::vector<std::uint8_t> marked;
    // The marked cells, each once, in the order marked: a refill visits these, not every cell's
    // flag (a frame marks a few dozen of a thousand cells). The order does not change a sum.
    std::vector<std::int32_t> marked_cells;
    void mark_cell(std::int32_t c) {
      auto& flag = marked[static_cast<std::size_t>(c)];
      if (flag) return;
      flag = 1;
      marked_cells.push_back(c);
    }
    void clear_marks() {
      for (const std::int32_t c : marked_cells) marked[static_cast<std::size_t>(c)] = 0;
      marked_cells.clear();
    }
    std::int32_t find(std::uint64_t key) const;  // its cell, or -1
    std::int32_t find_or_insert(std::uint64_t key, bool* inserted);
    void grow();
  };
  // Level-0 cell coordinates of x (clamped); level k's are these shifted right by k.
  static glm::ivec3 base_cell(const glm::dvec3& x);
  static std::uint64_t pack(const glm::ivec3& c);
  static constexpr double cell_m(int level) { return kBaseCellM * double(1 << level); }
  // Inserts the cell of level `level` at coordinates c (and its ancestors); its index.
  std::int32_t insert(int level, const glm::ivec3& c);
  // The sums around a point, interpolated (in double: they are read, not stored).
  struct Gathered {
    Sh9Rgb sh;
    double weight = 0.0;
    double time = 0.0;
  };
  // Blends the per-level sums around p (gathered by gather(level, corners, weights, sums)).
  template <class Gather>
  static bool blend(const glm::dvec3& p, Gather&& gather, const Sums& total, Answer& out);

  // The member lists of every level, from cell_of_slot_ and the parents (after a build or an
  // append).
  void index_members();
  // Each level's sums over all its cells, then the total (the last step of fill()).
  void sum_up_from(std::size_t level);

  std::vector<Level> levels_ = std::vector<Level>(kLevels);
  std::vector<std::int32_t> cell_of_slot_;  // level-0 cell of each slot
  Sums total_;
  bool members_stale_ = true;  // built since the member lists were made (append() keeps them)
};

// ---- templates ---------------------------------------------------------------------------

template <class AddSlot>
void FarField::fill(AddSlot&& add) {
  for (Level& level : levels_) {
    for (Sums& s : level.cells) s = Sums{};
    level.clear_marks();
  }
  for (std::size_t i = 0; i < cell_of_slot_.size(); ++i) {
    add(i, levels_[0].cells[static_cast<std::size_t>(cell_of_slot_[i])]);
  }
  sum_up_from(0);
}

template <class AddSlot>
void FarField::refill_marked(AddSlot&& add) {
  if (members_stale_) {
    index_members();
    fill(add);
    return;
  }
  Level& base = levels_[0];
  for (const std::int32_t c : base.marked_cells) {
    const auto u = static_cast<std::size_t>(c);
    Sums& s = base.cells[u] = Sums{};
    for (std::int32_t m = base.first[u]; m < base.first[u + 1]; ++m) {
      add(static_cast<std::size_t>(base.members[static_cast<std::size_t>(m)]), s);
    }
  }
  for (std::size_t k = 0; k + 1 < levels_.size(); ++k) {
    Level& level = levels_[k];
    Level& up = levels_[k + 1];
    for (const std::int32_t c : level.marked_cells) {
      up.mark_cell(level.parent[static_cast<std::size_t>(c)]);
    }
    level.clear_marks();
    for (const std::int32_t c : up.marked_cells) {
      const auto u = static_cast<std::size_t>(c);
      Sums& to = up.cells[u] = Sums{};
      for (std::int32_t m = up.first[u]; m < up.first[u + 1]; ++m) {
        const Sums& from =
            level.cells[static_cast<std::size_t>(up.members[static_cast<std::size_t>(m)])];
        to.sh += from.sh;
        to.weight += from.weight;
        to.time += from.time;
      }
    }
  }
  levels_.back().clear_marks();
  sum_up_from(levels_.size() - 1);
}

template <class Gather>
bool FarField::blend(const glm::dvec3& p, Gather&& gather, const Sums& total, Answer& out) {
  if (!(total.weight > 0.0)) return false;
  Sh9Rgb acc;
  double time = 0.0, rest = 1.0;
  out.cell_m = 0.0;
  for (int k = 0; k < kLevels && rest > 0.0; ++k) {
    // The 8 cell centres around p: centres sit at (c + 0.5) x cell.
    const double inv = 1.0 / cell_m(k);
    const glm::dvec3 g = p * inv - 0.5;
    const glm::dvec3 lo = glm::floor(g);
    const glm::dvec3 f = g - lo;
    glm::ivec3 c0;
    for (int a = 0; a < 3; ++a) {
      // Far beyond the clamped cells: any value out of range finds no cell.
      c0[a] = static_cast<int>(std::clamp(lo[a], -4.0 * kCellCoordLimit, 4.0 * kCellCoordLimit));
    }
    double w8[8];
    for (int n = 0; n < 8; ++n) {
      w8[n] =
          ((n & 1) ? f.x : 1.0 - f.x) * ((n & 2) ? f.y : 1.0 - f.y) * ((n & 4) ? f.z : 1.0 - f.z);
    }
    Gathered s;
    gather(k, c0, w8, s);
    if (!(s.weight > 0.0)) continue;
    if (out.cell_m == 0.0) out.cell_m = cell_m(k);
    const double a = std::min(1.0, s.weight / kConfidence);
    const double per = rest * a / s.weight;
    sh_add_scaled(acc, s.sh, static_cast<float>(per));
    time += s.time * per;
    rest *= 1.0 - a;
  }
  if (rest > 0.0) {
    const double per = rest / total.weight;
    sh_add_scaled(acc, total.sh, static_cast<float>(per));
    time += total.time * per;
    if (out.cell_m == 0.0) out.cell_m = cell_m(kLevels - 1) * 2.0;
  }
  out.sh = acc;
  out.data_time = time;
  return true;
}

template <class AddSlot>
bool FarField::evaluate_reference(const glm::dvec3& p, std::span<const glm::dvec3> positions,
                                  AddSlot&& add, Answer& out) {
  // Every slot's sums, once; then per level the slots whose cell is one of p's 8.
  std::vector<Sums> own(positions.size());
  Sums total;
  for (std::size_t i = 0; i < positions.size(); ++i) {
    add(i, own[i]);
    total.sh += own[i].sh;
    total.weight += own[i].weight;
    total.time += own[i].time;
  }
  auto gather = [&](int k, const glm::ivec3& c0, const double* w8, Gathered& s) {
    for (std::size_t i = 0; i < positions.size(); ++i) {
      const glm::ivec3 c = base_cell(positions[i]) >> k;
      const glm::ivec3 d = c - c0;
      if (d.x < 0 || d.x > 1 || d.y < 0 || d.y > 1 || d.z < 0 || d.z > 1) continue;
      const double w = w8[d.x + 2 * d.y + 4 * d.z];
      s.sh += own[i].sh * static_cast<float>(w);
      s.weight += w * own[i].weight;
      s.time += w * own[i].time;
    }
  };
  return blend(p, gather, total, out);
}

}  // namespace ambisim
