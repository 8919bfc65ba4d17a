#pragma once
// A spatial index over probes with a support radius each (the ambisim planner's kernel reach),
// for the two queries its lookups and its planning make: every probe whose support may hold a
// point, and the nearest probe to a point.
//
// Why levels: the supports span a factor of 3-5 (1.5 spacings, from 1.5 m refined spacing next
// to the camera to 4.8 m at 160 m) and more with other parameters. One grid sized for the
// largest support would hand a lookup near the camera three to four times the candidates. Each
// probe goes into the level whose cell is the smallest of the geometric series 1 m * 2^L that is
// at least its diameter; a ball of that radius around a point then meets at most two cells per
// axis (the point's and the neighbour on the side of the nearer face), so a lookup reads at most
// 8 cells per occupied level. It reads the neighbour across an axis only when the point lies
// within the level's largest reach of that face (3.7 cells per level instead of 8 at
// BM_Lookup/ambisim/10000), and a one-hash filter per level (CellFilter, 2 bytes per cell)
// answers most finds of an empty cell without touching the table. Ratio 2 rather than sqrt(2):
// twice the candidates per cell, which the float test below makes cheap, for half the levels and
// hash finds (BM_Lookup/ambisim/10000 644 -> 603 ns).
//
// Each level is a flat open-addressing hash table of cells (power-of-two capacity, load at most
// one half) holding ranges of one array of probe slots, built by a counting sort: O(n) to build,
// no allocation per cell, and a cell read is one or two cache lines. Beside each slot the level
// keeps its position relative to its cell's corner and its radius, in float (16 bytes): a lookup
// tests its candidates there, streaming one cell's entries, and touches a probe's own record
// only when its support holds the point (about one candidate in five passes). The index is rebuilt
// when the probe set changes (the planner does so once per frame at most; probes delivered between
// rebuilds are passed to queries as a short unindexed tail).
//
// Input ranges: positions finite and within +-2^20 cells of the origin (1,000 km: the float
// offsets of a clamped probe would be meaningless); radii > 0 and finite. Points far outside every
// occupied cell (beyond the world) are fine: cell coordinates are clamped to +-2^20 cells, which
// only makes a far point's candidates an empty set, and nearest() falls back to a scan of a level
// when its rings would find more cells than the level holds probes.
//
// nearest() searches rings of cells around the point, every level's first two rings before any
// level's further ones, and skips cells and columns (a second filter, over (x, y)) farther than
// the best so far, and slots whose float offsets are: only a slot that may be nearer costs a
// read of the caller's probe. Exact: the least squared distance in double, ties to the lower
// slot, as a scan of every slot gives.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "policies/ambisim/cell_filter.h"
#include "policies/ambisim/cell_key.h"

namespace ambisim {

class ProbeIndex {
 public:
  // Rebuilds from slots 0..n-1: positions[i] and radii[i] (> 0). The index keeps no copy of
  // the positions: nearest() is handed them again.
  void build(std::span<const glm::dvec3> positions, std::span<const double> radii);
  std::size_t size() const { return size_; }

  // Calls visit(slot) for every slot whose radius may reach p: a superset of the slots with
  // distance(p, position) < radius (the caller tests the distance exactly), tight to within
  // kReachMarginM. Each slot at most once.
  template <class Visit>
  void for_each_candidate(const glm::dvec3& p, Visit&& visit) const;

  // The slot nearest to p among those accept(slot) returns true for (ties: the lower slot),
  // or -1 when none; its distance in *distance. position_of(slot) gives the position the index
  // was built with.
  template <class PositionOf, class Accept>
  std::int64_t nearest(const glm::dvec3& p, PositionOf&& position_of, Accept&& accept,
                       double* distance) const;

  // Whether a slot that accept(slot) returns true for lies within r of p (r >= 0).
  template <class PositionOf, class Accept>
  bool any_within(const glm::dvec3& p, double r, PositionOf&& position_of, Accept&& accept) const;

  // Bytes held (cell tables and slot arrays), for PlannerStats.
  std::size_t bytes() const;

 private:
  struct Cell {
    std::uint64_t key = kEmpty;
    std::uint32_t begin = 0;
    std::uint32_t count = 0;
  };
  // A slot's position relative to its cell's lower corner and its radius squared, widened by
  // kReachMarginM: in float the offsets (< a few cells) are good to 1e-6 m, far inside it.
  struct Reach {
    float x, y, z, r2;
  };
  struct Level {
    double cell_m = 1.0;
    double inv_cell = 1.0;
    double reach_m = 0.0;              // the largest radius in the level, widened by kReachMarginM
    std::vector<Cell> table;           // open addressing, capacity a power of two
    std::vector<std::uint32_t> slots;  // the level's slots, grouped by cell
    std::vector<Reach> reach;          // beside slots
    glm::ivec3 lo{0}, hi{-1};          // bounds of the occupied cell coordinates
    CellFilter filter;                 // which cells may be occupied
    CellFilter columns;                // which columns (x, y) may hold an occupied cell
    const Cell* find(std::uint64_t key) const;
    const Cell* find(std::uint64_t key, std::size_t h) const;
    Cell* find_or_insert(std::uint64_t key);
  };
  static constexpr std::uint64_t kEmpty = kEmptyCellKey;
  static constexpr double kReachMarginM = 1e-4;
  // How far beyond the best distance so far nearest() still reads a cell or a slot: the cell
  // distances and the best are rounded doubles (relative and absolute slack), and a slot's
  // float offset from its cell's corner is good to 2^-24 of the cell per axis (kOffsetError
  // cells, with room: a cell of 2^30 m is off by up to 110 m).
  static constexpr double kNearestSlack = 1e-5;
  static constexpr double kNearestSlackM = 1e-3;
  static constexpr double kOffsetError = 2e-7;
  static constexpr int kCoordLimit = kCellCoordLimit;
  static int cell_coord(double v, double inv_cell);
  static int clamp_cell(double floored);  // cell_coord of a value already floored
  static std::uint64_t pack(int x, int y, int z);
  // The key of column (x, y) in Level::columns: the packed cell at height 0 (another filter).
  static std::uint64_t column_key(int x, int y) { return pack(x, y, 0); }
  static std::size_t hash(std::uint64_t key);

  // The cell at (x, y, z), or nullptr (outside the occupied box or empty).
  static const Cell* find_cell(const Level& level, int x, int y, int z);
  template <class Visit>
  static void visit_cell(const Level& level, int x, int y, int z, Visit&& visit);

  std::size_t size_ = 0;
  std::vector<Level> levels_;  // only the occupied ones, finest first
};

inline int ProbeIndex::cell_coord(double v, double inv_cell) {
  return clamp_cell(std::floor(v * inv_cell));
}

inline int ProbeIndex::clamp_cell(double c) {
  if (!(c > -kCoordLimit)) return -kCoordLimit;  // also NaN
  if (c >= kCoordLimit) return kCoordLimit;
  return static_cast<int>(c);
}

inline std::uint64_t ProbeIndex::pack(int x, int y, int z) { return pack_cell(x, y, z); }

inline std::size_t ProbeIndex::hash(std::uint64_t key) { return hash_cell_key(key); }

inline const ProbeIndex::Cell* ProbeIndex::Level::find(std::uint64_t key) const {
  return find(key, hash(key));
}

inline const ProbeIndex::Cell* ProbeIndex::Level::find(std::uint64_t key, std::size_t h) const {
  const std::size_t mask = table.size() - 1;
  for (std::size_t i = h & mask;; i = (i + 1) & mask) {
    const Cell& c = table[i];
    if (c.key == key) return &c;
    if (c.key == kEmpty) return nullptr;
  }
}

inline const ProbeIndex::Cell* ProbeIndex::find_cell(const Level& level, int x, int y, int z) {
  if (x < level.lo.x || x > level.hi.x || y < level.lo.y || y > level.hi.y || z < level.lo.z ||
      z > level.hi.z) {
    return nullptr;
  }
  const std::uint64_t key = pack(x, y, z);
  const std::size_t h = hash(key);
  if (!level.filter.may_hold(h)) return nullptr;
  return level.find(key, h);
}

template <class Visit>
void ProbeIndex::visit_cell(const Level& level, int x, int y, int z, Visit&& visit) {
  const Cell* c = find_cell(level, x, y, z);
  if (c == nullptr) return;
  const std::uint32_t* s = level.slots.data() + c->begin;
  for (std::uint32_t k = 0; k < c->count; ++k) visit(s[k]);
}

template <class Visit>
void ProbeIndex::for_each_candidate(const glm::dvec3& p, Visit&& visit) const {
  auto visit_reaching = [&](const Level& level, int x, int y, int z) {
    const Cell* c = find_cell(level, x, y, z);
    if (c == nullptr) return;
    // p relative to the cell's corner, in double, then float: within a few cells of it.
    const auto px = static_cast<float>(p.x - x * level.cell_m);
    const auto py = static_cast<float>(p.y - y * level.cell_m);
    const auto pz = static_cast<float>(p.z - z * level.cell_m);
    const std::uint32_t* s = level.slots.data() + c->begin;
    const Reach* r = level.reach.data() + c->begin;
    for (std::uint32_t k = 0; k < c->count; ++k) {
      const float dx = r[k].x - px, dy = r[k].y - py, dz = r[k].z - pz;
      if (dx * dx + dy * dy + dz * dz < r[k].r2) visit(s[k]);
    }
  };
  for (const Level& level : levels_) {
    // The ball of radius <= cell / 2 around p meets the cell holding p and, per axis, the
    // neighbour on the side of the nearer face.
    // One floor per axis serves both the cell and p's place in it (without SSE4.1 a floor is a
    // dozen instructions, and this loop used to take two per axis).
    const double fx = p.x * level.inv_cell, fy = p.y * level.inv_cell, fz = p.z * level.inv_cell;
    const double gx = std::floor(fx), gy = std::floor(fy), gz = std::floor(fz);
    const int x = clamp_cell(gx), y = clamp_cell(gy), z = clamp_cell(gz);
    const double ux = fx - gx, uy = fy - gy, uz = fz - gz;
    const int dx = ux < 0.5 ? -1 : 1, dy = uy < 0.5 ? -1 : 1, dz = uz < 0.5 ? -1 : 1;
    // The neighbour across an axis only where p lies within the level's largest reach of that
    // face (on average about half the time: a level's radii span a factor of 2 below half its
    // cell): the cells skipped hold no probe whose support reaches p.
    const double reach = level.reach_m * level.inv_cell;
    const int nx = std::min(ux, 1.0 - ux) < reach ? 1 : 0;
    const int ny = std::min(uy, 1.0 - uy) < reach ? 2 : 0;
    const int nz = std::min(uz, 1.0 - uz) < reach ? 4 : 0;
    const int wanted = nx | ny | nz;
    for (int k = 0; k < 8; ++k) {
      if ((k & ~wanted) != 0) continue;
      visit_reaching(level, x + ((k & 1) ? dx : 0), y + ((k & 2) ? dy : 0), z + ((k & 4) ? dz : 0));
    }
  }
}

template <class PositionOf, class Accept>
std::int64_t ProbeIndex::nearest(const glm::dvec3& p, PositionOf&& position_of, Accept&& accept,
                                 double* distance) const {
  double best2 = std::numeric_limits<double>::infinity();
  // The best distance widened by the slack (kNearestSlack): a cell or a slot (its float
  // offset, widened further) farther than this cannot be nearer, nor tie, in double.
  double screen_m = best2;  // infinite, as best2, until a slot is found
  double screen2 = best2;
  std::int64_t best = -1;
  auto consider = [&](std::uint32_t s) {
    if (!accept(s)) return;
    const glm::dvec3 d = position_of(s) - p;
    const double d2 = d.x * d.x + d.y * d.y + d.z * d.z;
    if (d2 < best2 || (d2 == best2 && static_cast<std::int64_t>(s) < best)) {
      best2 = d2;
      best = s;
      screen_m = std::sqrt(d2) * (1.0 + kNearestSlack) + kNearestSlackM;
      screen2 = screen_m * screen_m;
    }
  };
  // A cell's slots screened by their float offsets first: only those that may beat the best
  // so far cost a read of the caller's probe (its position and whether it is accepted), a cache
  // miss each.
  auto screen_cell = [&](const Level& level, const Cell& c, int cx, int cy, int cz) {
    const double px = p.x - cx * level.cell_m, py = p.y - cy * level.cell_m,
                 pz = p.z - cz * level.cell_m;
    const std::uint32_t* slot = level.slots.data() + c.begin;
    const Reach* r = level.reach.data() + c.begin;
    for (std::uint32_t k = 0; k < c.count; ++k) {
      const double dx = r[k].x - px, dy = r[k].y - py, dz = r[k].z - pz;
      const double lim = screen_m + kOffsetError * level.cell_m;  // screen_m moves in consider
      if (dx * dx + dy * dy + dz * dz <= lim * lim) consider(slot[k]);
    }
  };
  // Each level is searched in rings of cells around p's cell. All levels' first two rings
  // come first, so that whichever level holds a probe near p bounds every level's further
  // rings (levels hold probes by support, not by place: near the camera the fine level's, away
  // from it only the coarse one's).
  struct Search {
    int x = 0, y = 0, z = 0;        // p's cell
    double ux = 0, uy = 0, uz = 0;  // p in cells from that cell's corner: [0, 1) unless clamped
    int ring = 0;                   // the next ring
    bool done = false;
    std::size_t finds = 0;
  };
  auto start = [&](const Level& level) {
    Search s;
    s.x = cell_coord(p.x, level.inv_cell);
    s.y = cell_coord(p.y, level.inv_cell);
    s.z = cell_coord(p.z, level.inv_cell);
    s.ux = p.x * level.inv_cell - s.x;
    s.uy = p.y * level.inv_cell - s.y;
    s.uz = p.z * level.inv_cell - s.z;
    return s;
  };
  // As many levels as radii from 1 m to 4,000 km (more only with radii spanning more: those
  // levels are searched after, one at a time).
  constexpr std::size_t kInterleavedLevels = 24;
  const std::size_t interleaved = std::min(levels_.size(), kInterleavedLevels);
  std::array<Search, kInterleavedLevels> searches;
  for (std::size_t l = 0; l < interleaved; ++l) searches[l] = start(levels_[l]);
  auto beyond = [](int i, double u) {  // from u to the cell interval [i, i + 1], in cells
    return std::max({0.0, i - u, u - (i + 1)});
  };
  auto search = [&](const Level& level, Search& s, int last_ring) {
    // Cell finds cost more than screening one slot: past as many finds as the level holds
    // slots, its remaining cells are screened by a walk of its table instead (a slot screened
    // twice changes nothing).
    const std::size_t find_limit = level.slots.size() + 27;
    auto scan = [&] {
      for (const Cell& c : level.table) {
        if (c.key == kEmpty) continue;
        int cx, cy, cz;
        unpack_cell(c.key, cx, cy, cz);
        screen_cell(level, c, cx, cy, cz);
      }
      s.done = true;
    };
    const int x = s.x, y = s.y, z = s.z;
    for (; !s.done && s.ring <= last_ring; ++s.ring) {
      const int ring = s.ring;
      // Every cell of ring k is at least (k - 1) cells away from p.
      const double bound = static_cast<double>(ring - 1) * level.cell_m;
      if (ring > 0 && bound > 0.0 && bound * bound > best2) {
        s.done = true;
        break;
      }
      // Past the occupied box on every side: nothing more in this level.
      if (x - ring < level.lo.x && x + ring > level.hi.x && y - ring < level.lo.y &&
          y + ring > level.hi.y && z - ring < level.lo.z && z + ring > level.hi.z) {
        s.done = true;
        break;
      }
      // The ring's cells inside the occupied box, and of those only the ones nearer to p than
      // the best so far (in cells squared): the others cannot hold a nearer slot.
      const int i0 = std::max(-ring, level.lo.x - x), i1 = std::min(ring, level.hi.x - x);
      const int j0 = std::max(-ring, level.lo.y - y), j1 = std::min(ring, level.hi.y - y);
      const int k0 = std::max(-ring, level.lo.z - z), k1 = std::min(ring, level.hi.z - z);
      for (int i = i0; i <= i1 && !s.done; ++i) {
        const double gi = beyond(i, s.ux);
        const double gi2 = gi * gi;
        if (gi2 > screen2 * level.inv_cell * level.inv_cell) continue;
        for (int j = j0; j <= j1 && !s.done; ++j) {
          const double gj = beyond(j, s.uy);
          const double gij2 = gi2 + gj * gj;
          if (gij2 > screen2 * level.inv_cell * level.inv_cell) continue;
          // Over terrain most columns of the ball around p hold no cell of a level: one bit
          // answers for the column's whole height (without it nearest() searched a ball of
          // cells, most of them empty, for every object that appeared: 1.6 -> 0.6 us per search
          // in bench_planners' frame with 1e3 objects, and 0.35 us with it). A column's test
          // counts as a find: with nothing accepted, rings grow until the scan.
          if (++s.finds > find_limit) return scan();
          if (!level.columns.may_hold(hash(column_key(x + i, y + j)))) continue;
          auto visit = [&](int k) {
            if (s.done) return;
            const double gk = beyond(k, s.uz);
            if (gij2 + gk * gk > screen2 * level.inv_cell * level.inv_cell) return;
            if (++s.finds > find_limit) return scan();
            if (const Cell* c = find_cell(level, x + i, y + j, z + k)) {
              screen_cell(level, *c, x + i, y + j, z + k);
            }
          };
          const bool edge_ij = i == -ring || i == ring || j == -ring || j == ring;
          if (edge_ij) {
            for (int k = k0; k <= k1; ++k) visit(k);
          } else {
            if (k0 == -ring) visit(-ring);
            if (ring > 0 && k1 == ring) visit(ring);
          }
        }
      }
    }
  };
  constexpr int kAllRings = std::numeric_limits<int>::max();
  for (std::size_t l = 0; l < interleaved; ++l) search(levels_[l], searches[l], 1);
  for (std::size_t l = 0; l < interleaved; ++l) search(levels_[l], searches[l], kAllRings);
  for (std::size_t l = interleaved; l < levels_.size(); ++l) {
    Search s = start(levels_[l]);
    search(levels_[l], s, kAllRings);
  }
  *distance = best >= 0 ? std::sqrt(best2) : std::numeric_limits<double>::infinity();
  return best;
}

template <class PositionOf, class Accept>
bool ProbeIndex::any_within(const glm::dvec3& p, double r, PositionOf&& position_of,
                            Accept&& accept) const {
  const double r2 = r * r;
  bool found = false;
  auto test = [&](std::uint32_t s) {
    if (found || !accept(s)) return;
    const glm::dvec3 d = position_of(s) - p;
    found = d.x * d.x + d.y * d.y + d.z * d.z <= r2;
  };
  for (const Level& level : levels_) {
    const double inv = level.inv_cell;
    const int x0 = cell_coord(p.x - r, inv), x1 = cell_coord(p.x + r, inv);
    const int y0 = cell_coord(p.y - r, inv), y1 = cell_coord(p.y + r, inv);
    const int z0 = cell_coord(p.z - r, inv), z1 = cell_coord(p.z + r, inv);
    const auto cells = static_cast<double>(x1 - x0 + 1) * (y1 - y0 + 1) * (z1 - z0 + 1);
    if (cells > static_cast<double>(level.slots.size())) {
      for (std::uint32_t s : level.slots) test(s);
    } else {
      for (int x = x0; x <= x1 && !found; ++x) {
        for (int y = y0; y <= y1 && !found; ++y) {
          for (int z = z0; z <= z1 && !found; ++z) visit_cell(level, x, y, z, test);
        }
      }
    }
    if (found) return true;
  }
  return false;
}

}  // namespace ambisim
