#include "policies/ambisim/far_field.h"

#include <algorithm>
#include <array>

namespace ambisim {
namespace {

constexpr int kCoordLimit = kCellCoordLimit;
constexpr std::uint64_t kEmpty = kEmptyCellKey;

}  // namespace

glm::ivec3 FarField::base_cell(const glm::dvec3& x) {
  glm::ivec3 c;
  for (int a = 0; a < 3; ++a) {
    const double v = std::floor(x[a] * (1.0 / kBaseCellM));
    c[a] = !(v > -kCoordLimit)    ? -kCoordLimit
           : v >= kCoordLimit - 1 ? kCoordLimit - 1
                                  : static_cast<int>(v);
  }
  return c;
}

std::uint64_t FarField::pack(const glm::ivec3& c) { return pack_cell(c.x, c.y, c.z); }

std::int32_t FarField::Level::find(std::uint64_t key) const {
  const std::size_t h = hash_cell_key(key);
  if (!filter.may_hold(h)) return -1;
  const std::size_t mask = keys.size() - 1;
  for (std::size_t i = h & mask;; i = (i + 1) & mask) {
    if (keys[i] == key) return index[i];
    if (keys[i] == kEmpty) return -1;
  }
}

void FarField::Level::grow() {
  const std::size_t capacity = std::max<std::size_t>(16, 2 * keys.size());
  keys.assign(capacity, kEmpty);
  index.assign(capacity, -1);
  filter.reset(capacity / 2);  // find_or_insert keeps the load at most one half
  const std::size_t mask = capacity - 1;
  for (std::size_t c = 0; c < cell_keys.size(); ++c) {
    const std::size_t h = hash_cell_key(cell_keys[c]);
    filter.add(h);
    std::size_t i = h & mask;
    while (keys[i] != kEmpty) i = (i + 1) & mask;
    keys[i] = cell_keys[c];
    index[i] = static_cast<std::int32_t>(c);
  }
}

std::int32_t FarField::Level::find_or_insert(std::uint64_t key, bool* inserted) {
  *inserted = false;
  // Load at most one half: a probe sequence is short.
  if (2 * (cell_keys.size() + 1) > keys.size()) grow();
  const std::size_t mask = keys.size() - 1;
  std::size_t i = hash_cell_key(key) & mask;
  for (; keys[i] != kEmpty; i = (i + 1) & mask) {
    if (keys[i] == key) return index[i];
  }
  keys[i] = key;
  filter.add(hash_cell_key(key));
  index[i] = static_cast<std::int32_t>(cells.size());
  cells.emplace_back();
  cell_keys.push_back(key);
  parent.push_back(-1);
  *inserted = true;
  return index[i];
}

std::int32_t FarField::insert(int level, const glm::ivec3& c) {
  Level& l = levels_[static_cast<std::size_t>(level)];
  bool inserted = false;
  const std::int32_t cell = l.find_or_insert(pack(c), &inserted);
  if (inserted && level + 1 < kLevels) {
    const std::int32_t up = insert(level + 1, c >> 1);
    levels_[static_cast<std::size_t>(level)].parent[static_cast<std::size_t>(cell)] = up;
  }
  return cell;
}

void FarField::sum_up_from(std::size_t from) {
  total_ = Sums{};
  for (std::size_t k = from; k < levels_.size(); ++k) {
    const Level& level = levels_[k];
    if (k + 1 < levels_.size()) {
      for (Sums& s : levels_[k + 1].cells) s = Sums{};
    }
    for (std::size_t c = 0; c < level.cells.size(); ++c) {
      const Sums& s = level.cells[c];
      Sums& to = k + 1 < levels_.size()
                     ? levels_[k + 1].cells[static_cast<std::size_t>(level.parent[c])]
                     : total_;
      to.sh += s.sh;
      to.weight += s.weight;
      to.time += s.time;
    }
  }
}

void FarField::mark(std::size_t slot) {
  if (members_stale_) return;  // the next refill is a full one
  levels_[0].mark_cell(cell_of_slot_[slot]);
}

void FarField::index_members() {
  // Level 0's members are slots (by cell_of_slot_), a level's above are its children's cells
  // (by their parent), each list in ascending order: a counting sort.
  for (std::size_t k = 0; k < levels_.size(); ++k) {
    Level& level = levels_[k];
    const std::size_t cells = level.cells.size();
    level.first.assign(cells + 1, 0);
    level.marked.assign(cells, 0);
    level.marked_cells.clear();
    const std::size_t n = k == 0 ? cell_of_slot_.size() : levels_[k - 1].cells.size();
    auto owner = [&](std::size_t i) {
      return static_cast<std::size_t>(k == 0 ? cell_of_slot_[i] : levels_[k - 1].parent[i]);
    };
    for (std::size_t i = 0; i < n; ++i) ++level.first[owner(i) + 1];
    for (std::size_t c = 0; c < cells; ++c) level.first[c + 1] += level.first[c];
    level.members.resize(n);
    std::vector<std::int32_t> at(level.first.begin(), level.first.end() - 1);
    for (std::size_t i = 0; i < n; ++i) {
      level.members[static_cast<std::size_t>(at[owner(i)]++)] = static_cast<std::int32_t>(i);
    }
  }
  members_stale_ = false;
}

void FarField::build(std::span<const glm::dvec3> positions) {
  for (Level& l : levels_) l = Level{};
  members_stale_ = true;
  cell_of_slot_.clear();
  cell_of_slot_.reserve(positions.size());
  total_ = Sums{};
  for (const auto& x : positions) append(x);
}

void FarField::append(const glm::dvec3& position) {
  std::array<std::size_t, kLevels> cells_before{};
  for (std::size_t k = 0; k < levels_.size(); ++k) cells_before[k] = levels_[k].cells.size();
  const std::int32_t cell = insert(0, base_cell(position));
  cell_of_slot_.push_back(cell);
  if (members_stale_) return;  // the next refill indexes every member anyway
  // Keep the member lists instead of making them again (with a full fill) at the next refill:
  // the planner appends a probe on most deliveries, and the full fill after each one was about
  // a quarter of its update() (BM_Frame/ambisim/1000). The new slot is the highest, and a new cell
  // the highest of its level, so each goes last in its owner's list: the lists stay in ascending
  // order, as index_members() makes them, and the refill sums in the same order.
  auto add_member = [](Level& level, std::size_t owner, std::int32_t member) {
    level.members.insert(level.members.begin() + level.first[owner + 1], member);
    for (std::size_t c = owner + 1; c < level.first.size(); ++c) ++level.first[c];
  };
  for (std::size_t k = 0; k < levels_.size(); ++k) {
    Level& level = levels_[k];
    for (std::size_t c = cells_before[k]; c < level.cells.size(); ++c) {
      level.first.push_back(level.first.back());
      level.marked.push_back(0);
    }
    if (k == 0) {
      add_member(level, static_cast<std::size_t>(cell), static_cast<std::int32_t>(size() - 1));
    } else {
      const Level& below = levels_[k - 1];
      for (std::size_t c = cells_before[k - 1]; c < below.cells.size(); ++c) {
        add_member(level, static_cast<std::size_t>(below.parent[c]), static_cast<std::int32_t>(c));
      }
    }
  }
  // Its cell is redone at the next refill (a new cell's ancestors with it: they are marked up
  // from it).
  levels_[0].mark_cell(cell);
}

bool FarField::evaluate(const glm::dvec3& p, Answer& out, CornerMemo* memo) const {
  auto gather = [&](int k, const glm::ivec3& c0, const double* w8, Gathered& s) {
    const Level& level = levels_[static_cast<std::size_t>(k)];
    auto add = [&](int n, std::int32_t i) {
      const Sums& cell = level.cells[static_cast<std::size_t>(i)];
      sh_add_scaled(s.sh, cell.sh, static_cast<float>(w8[n]));
      s.weight += w8[n] * cell.weight;
      s.time += w8[n] * cell.time;
    };
    const int lo = -kCoordLimit >> k, hi = (kCoordLimit - 1) >> k;
    // Corners c0 + (n & 1, (n >> 1) & 1, (n >> 2) & 1). Where all 8 lie in range (every point
    // within 8,000 km) their keys are c0's plus a step (cell_key_step), under one range test:
    // a test and a packing per corner took about a fifth of the far field's instructions.
    const bool inside =
        c0.x >= lo && c0.x < hi && c0.y >= lo && c0.y < hi && c0.z >= lo && c0.z < hi;
    if (!inside) {
      for (int n = 0; n < 8; ++n) {
        const glm::ivec3 c = c0 + glm::ivec3(n & 1, (n >> 1) & 1, (n >> 2) & 1);
        if (c.x < lo || c.x > hi || c.y < lo || c.y > hi || c.z < lo || c.z > hi) continue;
        const std::int32_t i = level.find(pack(c));
        if (i >= 0) add(n, i);
      }
      return;
    }
    const std::uint64_t key0 = pack(c0);
    auto corner_cell = [&](int n) {
      return level.find(key0 + cell_key_step(n & 1, (n >> 1) & 1, (n >> 2) & 1));
    };
    if (memo == nullptr) {
      for (int n = 0; n < 8; ++n) {
        const std::int32_t i = corner_cell(n);
        if (i >= 0) add(n, i);
      }
      return;
    }
    std::vector<CornerMemo::Block>& blocks = memo->levels_[static_cast<std::size_t>(k)];
    if (blocks.empty()) blocks.resize(memo->blocks_);
    CornerMemo::Block& b = blocks[hash_cell_key(key0) & (memo->blocks_ - 1)];
    if (b.key != key0) {
      b.key = key0;
      b.count = 0;
      for (int n = 0; n < 8; ++n) {
        const std::int32_t i = corner_cell(n);
        if (i < 0) continue;
        b.cell[b.count] = i;
        b.corner[b.count++] = static_cast<std::uint8_t>(n);
      }
    }
    for (int j = 0; j < b.count; ++j) add(b.corner[j], b.cell[j]);
  };
  return blend(p, gather, total_, out);
}

std::size_t FarField::bytes() const {
  std::size_t b = cell_of_slot_.capacity() * sizeof(std::int32_t);
  for (const Level& l : levels_) {
    b += l.keys.capacity() * sizeof(std::uint64_t) + l.index.capacity() * sizeof(std::int32_t) +
         l.filter.bytes() + l.cells.capacity() * sizeof(Sums) +
         l.cell_keys.capacity() * sizeof(std::uint64_t) +
         l.parent.capacity() * sizeof(std::int32_t) + l.first.capacity() * sizeof(std::int32_t) +
         l.members.capacity() * sizeof(std::int32_t) + l.marked.capacity() +
         l.marked_cells.capacity() * sizeof(std::int32_t);
  }
  return b;
}

}  // namespace ambisim
