#pragma once
// Integer cell coordinates packed into one 64-bit hash-table key, and the key's hash: shared by
// the ambisim planner's spatial index (probe_index.h) and its far field (far_field.h).
//
// Input range: coordinates in [-kCellCoordLimit, kCellCoordLimit) per axis (21 bits each); the
// callers clamp. kEmptyCellKey is never a packed key (its top bit is set).
#include <cstddef>
#include <cstdint>

namespace ambisim {

inline constexpr int kCellCoordLimit = 1 << 20;
inline constexpr std::uint64_t kEmptyCellKey = ~std::uint64_t{0};

inline std::uint64_t pack_cell(int x, int y, int z) {
  constexpr std::uint64_t kMask = (std::uint64_t{1} << 21) - 1;
  const auto u = [](int v) { return static_cast<std::uint64_t>(v + kCellCoordLimit) & kMask; };
  return u(x) | (u(y) << 21) | (u(z) << 42);
}

// A bit mixer (splitmix64's): packed keys of neighbouring cells differ in low bits only.
inline std::size_t hash_cell_key(std::uint64_t key) {
  key ^= key >> 29;
  key *= 0xbf58476d1ce4e5b9ULL;
  key ^= key >> 32;
  return static_cast<std::size_t>(key);
}

}  // namespace ambisim
