#pragma once
// The probe lattice of the baked baselines (`baked`, `baked_tod`): what Unity's Adaptive Probe
// Volumes and Unreal's volumetric lightmaps build at bake time, reduced to a heightfield world.
//
// Levels. Level l has spacing spacing_m x 3^l (APV's bricks of 1/3/9/27 m: each level's
// points are also points of every finer level's lattice, so keys stay integers on a fixed
// world lattice, policies/core/lattice_key.h). Level l covers the route corridor (every
// column whose cell comes within corridor_m of the route in x, y) from the lowest surface
// (terrain or canopy top) under the cell up to band_m x 3^l above its highest, and the
// coarsest level up to top_m: the finest spacing sits within band_m of the surface, where
// geometry is and where the objects are, and each level up is 27 times sparser, so every
// coarser level costs about a ninth of the one below it. Where the surface rises steeply
// inside a cell (cutting walls, canopy edges) the cell's vertical span grows with it: finer
// probes where geometry is, as APV subdivides bricks that geometry intersects.
//
// Validity (APV's virtual offset). A lattice point below the surface (or within clearance_m
// above it, over a small stencil: the planner knows the surface only as an interpolated height)
// would see the inside of the terrain. It is moved to the nearest free point at most half its
// cell away (straight up, or up and sideways at 45 degrees, or sideways: 17 directions, the
// shortest move wins); the trilinear weights stay those of the lattice point, as APV offsets
// only where the probe is rendered from. A point that no such move frees is dropped: it takes
// no capture and lookups renormalise over the corners that remain. Both are counted.
//
// Budget (APV's memory budget). When the levels' points would exceed max_points the finest
// levels are left out, the coarsest kept first: a long route still bakes, only coarser.
//
// Lookup. The finest level whose cell containing p is part of the lattice and has at least
// one usable corner with non-zero weight: trilinear over the cell's corners, renormalised over
// the usable ones; then the next coarser level; none: the caller's default ambient.
#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include <glm/vec3.hpp>

#include "policies/core/lattice_key.h"

namespace ambisim {

struct BakedLatticeSettings {
  double spacing_m = 2.0;    // the finest level's spacing
  int levels = 4;            // spacing_m x 3^l for l = 0 .. levels - 1
  double corridor_m = 12.0;  // half-width of the corridor around the route (x, y)
  double band_m = 2.0;       // the finest level's height above the surface (x 3 per level)
  double top_m = 40.0;       // the coarsest level's height above the surface
  double clearance_m = 0.1;  // a free point is at least this far above the surface
  // The bake's budget in lattice points: finer levels are left out until the rest fit.
  double max_points = 1e6;
};

class BakedLattice {
 public:
  static constexpr int kRatio = 3;  // spacing ratio between levels (APV's bricks)
  // The surface's highest point this far around (a world cell's half-width in the shipped
  // worlds: the renderer's columns are flat-topped cells, the planner's surface interpolated),
  // sampled (2 kStencilSteps + 1)^2 times.
  static constexpr double kStencil_m = 1.0;
  static constexpr int kStencilSteps = 2;
  static constexpr double kReliefMargin = 0.25;  // x the relief on the stencil, above its top
  // Consecutive route points farther apart than this are a camera cut (a teleport): both
  // sides are baked, not the straight line between them.
  static constexpr double kRouteGap_m = 100.0;

  struct Probe {
    int level = 0;
    LatticeKey key;            // on the level's own lattice (metres = key x spacing)
    glm::dvec3 position{0.0};  // where it is rendered from (after any virtual offset)
    bool moved = false;
  };
  struct LevelCounts {
    std::int64_t columns = 0;  // lattice columns of the level
    std::int64_t points = 0;   // lattice points (probes kept + dropped)
    std::int64_t moved = 0;    // kept after a virtual offset
    std::int64_t dropped = 0;  // no free point within half a cell
  };
  // The cell that serves a lookup: its level, usable corners and normalised weights.
  struct Cell {
    int level = -1;  // -1: no level serves the point
    int count = 0;
    std::array<std::uint32_t, 8> probe{};
    std::array<double, 8> weight{};
  };
  using Surface = std::function<double(double, double)>;

  BakedLattice() = default;
  // The lattice around `route` (points of a polyline; one point is a disc) and around the
  // squares of side cell_m centred on `cells` (where the lit objects go), over `surface`.
  BakedLattice(const std::vector<glm::dvec3>& route, const Surface& surface,
               const BakedLatticeSettings& settings, const std::vector<glm::dvec3>& cells = {},
               double cell_m = 0.0);

  const BakedLatticeSettings& settings() const { return settings_; }
  double spacing(int level) const;
  // The probes kept, in the order built (finest level first): index i is probe i.
  std::size_t size() const { return probes_.size(); }
  Probe probe(std::size_t i) const;
  const glm::dvec3& position(std::size_t i) const { return probes_[i].position; }
  glm::dvec3 nominal_position(const Probe& q) const;
  const std::vector<LevelCounts>& counts() const { return counts_; }
  std::int64_t moved() const;
  std::int64_t dropped() const;
  // The finest level built (levels: none fitted the budget).
  int first_level() const { return first_level_; }

  // Free of the surface as the lattice tests it: z >= the highest surface within kStencil_m
  // (on the stencil) + kReliefMargin x the relief there + clearance_m.
  bool is_free(const Surface& surface, const glm::dvec3& p) const;

  // The serving cell for p; `usable(i)` says whether probe i holds data.
  Cell find(const glm::dvec3& p, const std::function<bool(std::uint32_t)>& usable) const;

  // Memory held: the probes, the two hash tables, the column ranges.
  std::int64_t bytes() const;

 private:
  // Open addressing with linear probing over one level's keys (stored as int32: 2^31 cells
  // from the origin, beyond any world); deterministic and allocation-free on lookup. Values are
  // indices; kEmpty marks a free slot.
  class Table {
   public:
    static constexpr std::uint32_t kEmpty = 0xFFFFFFFFu;
    static bool fits(const LatticeKey& k);
    // The value stored under k, or kEmpty.
    std::uint32_t find(const LatticeKey& k) const;
    // Inserts k -> value unless present (k must fit); returns the value stored.
    std::uint32_t insert(const LatticeKey& k, std::uint32_t value);
    std::int64_t bytes() const;

   private:
    struct Slot {
      std::int32_t x = 0, y = 0, z = 0;
      std::uint32_t value = kEmpty;
    };
    std::size_t slot_of(const LatticeKey& k) const;
    void rehash(std::size_t capacity);
    std::vector<Slot> slots_;
    std::size_t size_ = 0;
  };
  struct Column {
    std::int32_t k_lo = 0, k_hi = -1;  // the cells k_lo .. k_hi (inclusive) are the lattice's
  };
  struct Stored {
    glm::dvec3 position{0.0};
    std::array<std::int32_t, 3> key{};
    std::int8_t level = 0;
    bool moved = false;
  };
  static constexpr std::uint32_t kDropped = 0xFFFFFFFEu;  // a point without a probe

  BakedLatticeSettings settings_;
  std::vector<Stored> probes_;
  std::vector<Column> columns_;
  std::vector<Table> probe_index_;   // per level: point -> probe index or kDropped
  std::vector<Table> column_index_;  // per level: (i, j, 0) -> index into columns_
  std::vector<LevelCounts> counts_;
  int first_level_ = 0;
};

}  // namespace ambisim
