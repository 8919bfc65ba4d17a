#include "policies/baselines/baked_lattice.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include <glm/geometric.hpp>

#include "sim/base/hash.h"

namespace ambisim {
namespace {

// Beyond this many cells from the origin a coordinate is not a lattice index (the int64 cast
// would overflow); such points are outside every lattice.
constexpr double kMaxIndex = 1e15;

std::int64_t floor_index(double v) { return static_cast<std::int64_t>(std::floor(v)); }

// Distance in x, y from c to the segment a-b (a point when a = b).
double distance_xy(double cx, double cy, const glm::dvec3& a, const glm::dvec3& b) {
  const double ux = b.x - a.x, uy = b.y - a.y;
  const double len2 = ux * ux + uy * uy;
  double t = 0.0;
  if (len2 > 0.0) t = std::clamp(((cx - a.x) * ux + (cy - a.y) * uy) / len2, 0.0, 1.0);
  return std::hypot(cx - (a.x + t * ux), cy - (a.y + t * uy));
}

// The lowest free height at (x, y) before the clearance: the highest surface on the stencil,
// plus a quarter of the relief it spans. The planner's surface is interpolated between the
// renderer's flat-topped columns, and next to a column much higher than its neighbours (a
// canopy edge) the interpolated value on the stencil can sit up to that far below the top.
double free_height(const BakedLattice::Surface& surface, double x, double y) {
  double hi = -std::numeric_limits<double>::infinity(), lo = -hi;
  constexpr int n = BakedLattice::kStencilSteps;
  constexpr double step = BakedLattice::kStencil_m / n;
  for (int a = -n; a <= n; ++a) {
    for (int b = -n; b <= n; ++b) {
      const double h = surface(x + a * step, y + b * step);
      hi = std::max(hi, h);
      lo = std::min(lo, h);
    }
  }
  return hi + BakedLattice::kReliefMargin * (hi - lo);
}

// The 16 directions of the virtual offset besides straight up: 8 azimuths at 45 degrees up,
// then the same 8 level.
std::array<glm::dvec3, 16> offset_directions() {
  std::array<glm::dvec3, 16> d{};
  const double h = std::sqrt(0.5);
  for (int a = 0; a < 8; ++a) {
    const double az = a * 3.14159265358979323846 / 4.0;
    d[static_cast<std::size_t>(a)] = {h * std::cos(az), h * std::sin(az), h};
    d[static_cast<std::size_t>(8 + a)] = {std::cos(az), std::sin(az), 0.0};
  }
  return d;
}

// The nearest free point within max_move of q (q itself not free), or none: straight up by
// exactly what is needed, or the first free point along the other directions in steps of
// max_move / 8 when that is shorter.
std::optional<glm::dvec3> virtual_offset(const BakedLattice& lattice,
                                         const BakedLattice::Surface& surface, const glm::dvec3& q,
                                         double max_move) {
  static const std::array<glm::dvec3, 16> dirs = offset_directions();
  std::optional<glm::dvec3> best;
  double best_d = std::numeric_limits<double>::infinity();
  const double z_free = free_height(surface, q.x, q.y) + lattice.settings().clearance_m;
  if (z_free - q.z <= max_move) {
    best = glm::dvec3(q.x, q.y, z_free);
    best_d = z_free - q.z;
  }
  constexpr int kSteps = 8;
  for (int n = 1; n <= kSteps; ++n) {
    const double d = max_move * n / kSteps;
    if (d >= best_d) break;
    for (const auto& u : dirs) {
      const glm::dvec3 p = q + u * d;
      if (lattice.is_free(surface, p)) return p;
    }
  }
  return best;
}

}  // namespace

// ---- Table ----

bool BakedLattice::Table::fits(const LatticeKey& k) {
  constexpr std::int64_t lo = std::numeric_limits<std::int32_t>::min();
  constexpr std::int64_t hi = std::numeric_limits<std::int32_t>::max();
  return k.x >= lo && k.x <= hi && k.y >= lo && k.y <= hi && k.z >= lo && k.z <= hi;
}

void BakedLattice::Table::rehash(std::size_t capacity) {
  std::vector<Slot> old = std::move(slots_);
  slots_.assign(capacity, Slot{});
  size_ = 0;
  for (const auto& s : old) {
    if (s.value != kEmpty) insert({s.x, s.y, s.z}, s.value);
  }
}

std::size_t BakedLattice::Table::slot_of(const LatticeKey& k) const {
  std::uint64_t h = splitmix64(static_cast<std::uint64_t>(k.x));
  h = hash_combine(h, static_cast<std::uint64_t>(k.y));
  h = hash_combine(h, static_cast<std::uint64_t>(k.z));
  return static_cast<std::size_t>(h) & (slots_.size() - 1);
}

std::uint32_t BakedLattice::Table::find(const LatticeKey& k) const {
  if (slots_.empty() || !fits(k)) return kEmpty;
  for (std::size_t i = slot_of(k);; i = (i + 1) & (slots_.size() - 1)) {
    const Slot& s = slots_[i];
    if (s.value == kEmpty) return kEmpty;
    if (s.x == k.x && s.y == k.y && s.z == k.z) return s.value;
  }
}

std::uint32_t BakedLattice::Table::insert(const LatticeKey& k, std::uint32_t value) {
  // At most 3/4 full: a miss probes a few slots on average, at 16 bytes a slot.
  if (4 * (size_ + 1) > 3 * slots_.size()) rehash(std::max<std::size_t>(16, 2 * slots_.size()));
  for (std::size_t i = slot_of(k);; i = (i + 1) & (slots_.size() - 1)) {
    Slot& s = slots_[i];
    if (s.value == kEmpty) {
      s = {static_cast<std::int32_t>(k.x), static_cast<std::int32_t>(k.y),
           static_cast<std::int32_t>(k.z), value};
      ++size_;
      return value;
    }
    if (s.x == k.x && s.y == k.y && s.z == k.z) return s.value;
  }
}

std::int64_t BakedLattice::Table::bytes() const {
  return static_cast<std::int64_t>(slots_.capacity() * sizeof(Slot));
}

// ---- BakedLattice ----

BakedLattice::BakedLattice(const std::vector<glm::dvec3>& route, const Surface& surface,
                           const BakedLatticeSettings& settings,
                           const std::vector<glm::dvec3>& cells, double cell_m)
    : settings_(settings) {
  settings_.levels = std::max(settings_.levels, 1);
  const auto levels = static_cast<std::size_t>(settings_.levels);
  counts_.assign(levels, LevelCounts{});
  probe_index_.resize(levels);
  column_index_.resize(levels);
  if (route.empty() && cells.empty()) return;

  // 1. Every level's columns and their cell ranges (cheap: five surface samples a column).
  struct ColumnAt {
    std::int64_t i, j;
    Column cells;
  };
  std::vector<std::vector<ColumnAt>> level_columns(levels);
  for (int l = 0; l < settings_.levels; ++l) {
    const double s = spacing(l);
    const double height = l == settings_.levels - 1
                              ? settings_.top_m
                              : std::min(settings_.band_m * std::pow(kRatio, l), settings_.top_m);
    // Columns whose cell comes within corridor_m of the route: the cell's centre within
    // corridor_m + half its diagonal.
    const double route_reach = settings_.corridor_m + s * std::sqrt(0.5);
    std::vector<std::array<std::int64_t, 2>> cols;
    // The route's segments (each to the next point, or the point alone before a cut and at the
    // end), then the objects' squares as discs around their centres.
    const std::size_t segments = route.size() + cells.size();
    for (std::size_t n = 0; n < segments; ++n) {
      const bool on_route = n < route.size();
      const glm::dvec3& a = on_route ? route[n] : cells[n - route.size()];
      const bool joined =
          on_route && n + 1 < route.size() && glm::distance(a, route[n + 1]) <= kRouteGap_m;
      const glm::dvec3& b = joined ? route[n + 1] : a;
      // An object's square is covered as itself (it is where the object was, not a corridor
      // it may leave): its half-diagonal and the lattice cell's.
      const double reach = on_route ? route_reach : (cell_m + s) * std::sqrt(0.5);
      const std::int64_t i0 = floor_index((std::min(a.x, b.x) - reach) / s);
      const std::int64_t i1 = floor_index((std::max(a.x, b.x) + reach) / s);
      const std::int64_t j0 = floor_index((std::min(a.y, b.y) - reach) / s);
      const std::int64_t j1 = floor_index((std::max(a.y, b.y) + reach) / s);
      for (std::int64_t i = i0; i <= i1; ++i) {
        for (std::int64_t j = j0; j <= j1; ++j) {
          const double cx = (static_cast<double>(i) + 0.5) * s;
          const double cy = (static_cast<double>(j) + 0.5) * s;
          if (distance_xy(cx, cy, a, b) <= reach) cols.push_back({i, j});
        }
      }
    }
    std::sort(cols.begin(), cols.end());
    cols.erase(std::unique(cols.begin(), cols.end()), cols.end());
    auto& out = level_columns[static_cast<std::size_t>(l)];
    out.reserve(cols.size());
    for (const auto& [i, j] : cols) {
      // The surface's span over the cell: its corners and centre.
      const double x0 = static_cast<double>(i) * s, y0 = static_cast<double>(j) * s;
      double lo = std::numeric_limits<double>::infinity(), hi = -lo;
      static constexpr std::array<std::array<double, 2>, 5> kSamples{
          {{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}, {1.0, 1.0}, {0.5, 0.5}}};
      for (const auto& d : kSamples) {
        const double h = surface(x0 + d[0] * s, y0 + d[1] * s);
        lo = std::min(lo, h);
        hi = std::max(hi, h);
      }
      const LatticeKey k_lo{i, j, floor_index(lo / s)},
          k_hi{i + 1, j + 1, floor_index((hi + height) / s) + 1};
      if (!Table::fits(k_lo) || !Table::fits(k_hi)) continue;  // beyond any world
      out.push_back(
          {i, j, {static_cast<std::int32_t>(k_lo.z), static_cast<std::int32_t>(k_hi.z - 1)}});
    }
  }

  // 2. The bake's budget (APV's memory budget): the finest levels are left out, coarsest kept
  // first, until the points fit. Each column stands for the points on one of its corner
  // lines, so the estimate is close (the corridor's far edge adds one line).
  first_level_ = settings_.levels;
  double points = 0.0;
  for (int l = settings_.levels - 1; l >= 0; --l) {
    for (const auto& c : level_columns[static_cast<std::size_t>(l)]) {
      points += static_cast<double>(c.cells.k_hi - c.cells.k_lo + 2);
    }
    if (points > settings_.max_points) break;
    first_level_ = l;
  }

  // 3. The points of the levels kept, each tested and moved out or dropped once.
  for (int l = first_level_; l < settings_.levels; ++l) {
    const double s = spacing(l);
    LevelCounts& count = counts_[static_cast<std::size_t>(l)];
    const auto& cols = level_columns[static_cast<std::size_t>(l)];
    count.columns = static_cast<std::int64_t>(cols.size());
    Table& index = probe_index_[static_cast<std::size_t>(l)];
    for (const auto& [i, j, col] : cols) {
      column_index_[static_cast<std::size_t>(l)].insert(
          {i, j, 0}, static_cast<std::uint32_t>(columns_.size()));
      columns_.push_back(col);
      for (int c = 0; c < 4; ++c) {
        for (std::int64_t k = col.k_lo; k <= col.k_hi + 1; ++k) {
          const LatticeKey key{i + (c & 1), j + ((c >> 1) & 1), k};
          if (index.find(key) != Table::kEmpty) continue;
          ++count.points;
          Stored q;
          q.level = static_cast<std::int8_t>(l);
          q.key = {static_cast<std::int32_t>(key.x), static_cast<std::int32_t>(key.y),
                   static_cast<std::int32_t>(key.z)};
          q.position = glm::dvec3(key.x, key.y, key.z) * s;
          if (!is_free(surface, q.position)) {
            const auto moved = virtual_offset(*this, surface, q.position, 0.5 * s);
            if (!moved) {
              ++count.dropped;
              index.insert(key, kDropped);
              continue;
            }
            q.position = *moved;
            q.moved = true;
            ++count.moved;
          }
          index.insert(key, static_cast<std::uint32_t>(probes_.size()));
          probes_.push_back(q);
        }
      }
    }
  }
  probes_.shrink_to_fit();
  columns_.shrink_to_fit();
}

double BakedLattice::spacing(int level) const {
  return settings_.spacing_m * std::pow(static_cast<double>(kRatio), level);
}

BakedLattice::Probe BakedLattice::probe(std::size_t i) const {
  const Stored& q = probes_[i];
  return {q.level, {q.key[0], q.key[1], q.key[2]}, q.position, q.moved};
}

glm::dvec3 BakedLattice::nominal_position(const Probe& q) const {
  const double s = spacing(q.level);
  return {static_cast<double>(q.key.x) * s, static_cast<double>(q.key.y) * s,
          static_cast<double>(q.key.z) * s};
}

std::int64_t BakedLattice::moved() const {
  std::int64_t n = 0;
  for (const auto& c : counts_) n += c.moved;
  return n;
}

std::int64_t BakedLattice::dropped() const {
  std::int64_t n = 0;
  for (const auto& c : counts_) n += c.dropped;
  return n;
}

bool BakedLattice::is_free(const Surface& surface, const glm::dvec3& p) const {
  return p.z >= free_height(surface, p.x, p.y) + settings_.clearance_m;
}

BakedLattice::Cell BakedLattice::find(const glm::dvec3& p,
                                      const std::function<bool(std::uint32_t)>& usable) const {
  Cell cell;
  if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return cell;
  for (int l = first_level_; l < settings_.levels; ++l) {
    const glm::dvec3 u = p / spacing(l);
    if (std::abs(u.x) > kMaxIndex || std::abs(u.y) > kMaxIndex || std::abs(u.z) > kMaxIndex) {
      return cell;
    }
    const LatticeKey k0{floor_index(u.x), floor_index(u.y), floor_index(u.z)};
    const std::uint32_t c = column_index_[static_cast<std::size_t>(l)].find({k0.x, k0.y, 0});
    if (c == Table::kEmpty) continue;
    const Column& col = columns_[c];
    if (k0.z < col.k_lo || k0.z > col.k_hi) continue;
    const glm::dvec3 f = u - glm::dvec3(static_cast<double>(k0.x), static_cast<double>(k0.y),
                                        static_cast<double>(k0.z));
    double total = 0.0;
    int n = 0;
    for (int corner = 0; corner < 8; ++corner) {
      const int a = corner & 1, b = (corner >> 1) & 1, z = (corner >> 2) & 1;
      const std::uint32_t idx =
          probe_index_[static_cast<std::size_t>(l)].find({k0.x + a, k0.y + b, k0.z + z});
      if (idx == Table::kEmpty || idx == kDropped || !usable(idx)) continue;
      const double w = (a ? f.x : 1.0 - f.x) * (b ? f.y : 1.0 - f.y) * (z ? f.z : 1.0 - f.z);
      if (!(w > 0.0)) continue;
      cell.probe[static_cast<std::size_t>(n)] = idx;
      cell.weight[static_cast<std::size_t>(n)] = w;
      total += w;
      ++n;
    }
    if (n == 0) continue;
    for (int m = 0; m < n; ++m) cell.weight[static_cast<std::size_t>(m)] /= total;
    cell.level = l;
    cell.count = n;
    return cell;
  }
  return cell;
}

std::int64_t BakedLattice::bytes() const {
  std::int64_t tables = 0;
  for (const auto& t : probe_index_) tables += t.bytes();
  for (const auto& t : column_index_) tables += t.bytes();
  return static_cast<std::int64_t>(
             probes_.capacity() * sizeof(Stored) + columns_.capacity() * sizeof(Column) +
             counts_.capacity() * sizeof(LevelCounts) +
             (probe_index_.capacity() + column_index_.capacity()) * sizeof(Table)) +
         tables;
}

}  // namespace ambisim
