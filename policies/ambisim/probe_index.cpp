#include "policies/ambisim/probe_index.h"

#include <algorithm>
#include <bit>

#include <glm/common.hpp>

namespace ambisim {
namespace {

constexpr double kBaseCellM = 1.0;
constexpr double kLevelRatio = 2.0;  // probe_index.h says why not sqrt(2)

// The level whose cell, kBaseCellM * kLevelRatio^level, is the smallest at least twice
// `radius`: then a ball of that radius meets at most two cells per axis.
int level_for(double radius) {
  int level = 0;
  double cell = kBaseCellM;
  while (cell < 2.0 * radius) {
    cell *= kLevelRatio;
    ++level;
  }
  return level;
}

double cell_of_level(int level) {
  double cell = kBaseCellM;
  for (int i = 0; i < level; ++i) cell *= kLevelRatio;
  return cell;
}

}  // namespace

ProbeIndex::Cell* ProbeIndex::Level::find_or_insert(std::uint64_t key) {
  const std::size_t mask = table.size() - 1;
  for (std::size_t i = hash(key) & mask;; i = (i + 1) & mask) {
    Cell& c = table[i];
    if (c.key == key) return &c;
    if (c.key == kEmpty) {
      c.key = key;
      return &c;
    }
  }
}

void ProbeIndex::build(std::span<const glm::dvec3> positions, std::span<const double> radii) {
  size_ = positions.size();
  // Which level each slot goes to, and how many per level.
  std::vector<int> level_of(positions.size());
  int top = -1;
  for (std::size_t i = 0; i < positions.size(); ++i) {
    level_of[i] = level_for(radii[i]);
    top = std::max(top, level_of[i]);
  }
  std::vector<std::uint32_t> per_level(static_cast<std::size_t>(top + 1), 0);
  for (int l : level_of) ++per_level[static_cast<std::size_t>(l)];
  std::vector<int> dense(per_level.size(), -1);  // level number -> index in levels_
  levels_.clear();
  for (std::size_t l = 0; l < per_level.size(); ++l) {
    if (per_level[l] == 0) continue;
    dense[l] = static_cast<int>(levels_.size());
    Level level;
    level.cell_m = cell_of_level(static_cast<int>(l));
    level.inv_cell = 1.0 / level.cell_m;
    level.table.assign(std::bit_ceil(std::max<std::size_t>(2 * per_level[l], 8)), Cell{});
    level.slots.resize(per_level[l]);
    level.reach.resize(per_level[l]);
    level.lo = glm::ivec3(kCoordLimit);
    level.hi = glm::ivec3(-kCoordLimit);
    levels_.push_back(std::move(level));
  }
  // Counting sort: count per cell, prefix sums, then place (slots keep ascending order within a
  // cell, so visits are deterministic).
  std::vector<glm::ivec3> cell_of(positions.size());
  auto level_index = [&](std::size_t i) {
    return static_cast<std::size_t>(dense[static_cast<std::size_t>(level_of[i])]);
  };
  for (std::size_t i = 0; i < positions.size(); ++i) {
    Level& level = levels_[level_index(i)];
    level.reach_m = std::max(level.reach_m, radii[i] + 2.0 * kReachMarginM);
    const glm::dvec3& p = positions[i];
    const glm::ivec3 c(cell_coord(p.x, level.inv_cell), cell_coord(p.y, level.inv_cell),
                       cell_coord(p.z, level.inv_cell));
    level.lo = glm::min(level.lo, c);
    level.hi = glm::max(level.hi, c);
    cell_of[i] = c;
    ++level.find_or_insert(pack(c.x, c.y, c.z))->count;
  }
  for (Level& level : levels_) {
    // Sized for the probes, the table may hold far fewer cells: shrink it to a load of at most
    // one half of the cells (memory per probe is a target).
    std::size_t cells = 0;
    for (const Cell& c : level.table) cells += c.key != kEmpty ? 1 : 0;
    const std::size_t fitted = std::bit_ceil(std::max<std::size_t>(2 * cells, 8));
    if (fitted < level.table.size()) {
      std::vector<Cell> old = std::move(level.table);
      level.table.assign(fitted, Cell{});
      for (const Cell& c : old) {
        if (c.key != kEmpty) level.find_or_insert(c.key)->count = c.count;
      }
    }
    level.filter.reset(cells);
    level.columns.reset(cells);
    std::uint32_t next = 0;
    for (Cell& c : level.table) {
      if (c.key == kEmpty) continue;
      level.filter.add(hash(c.key));
      int cx, cy, cz;
      unpack_cell(c.key, cx, cy, cz);
      level.columns.add(hash(column_key(cx, cy)));
      c.begin = next;
      next += c.count;
      c.count = 0;
    }
  }
  for (std::size_t i = 0; i < positions.size(); ++i) {
    Level& level = levels_[level_index(i)];
    const glm::ivec3& c = cell_of[i];
    Cell* cell = level.find_or_insert(pack(c.x, c.y, c.z));
    const std::uint32_t at = cell->begin + cell->count++;
    level.slots[at] = static_cast<std::uint32_t>(i);
    const glm::dvec3& p = positions[i];
    const double r = radii[i] + kReachMarginM;
    level.reach[at] = {static_cast<float>(p.x - c.x * level.cell_m),
                       static_cast<float>(p.y - c.y * level.cell_m),
                       static_cast<float>(p.z - c.z * level.cell_m), static_cast<float>(r * r)};
  }
}

std::size_t ProbeIndex::bytes() const {
  std::size_t b = levels_.capacity() * sizeof(Level);
  for (const Level& level : levels_) {
    b += level.table.capacity() * sizeof(Cell) + level.slots.capacity() * sizeof(std::uint32_t) +
         level.reach.capacity() * sizeof(Reach) + level.filter.bytes() + level.columns.bytes();
  }
  return b;
}

}  // namespace ambisim
