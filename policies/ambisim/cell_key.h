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

inline constexpr int kCellKeyFieldBits = 21;  // per axis

inline std::uint64_t pack_cell(int x, int y, int z) {
  constexpr std::uint64_t kMask = (std::uint64_t{1} << kCellKeyFieldBits) - 1;
  const auto u = [](int v) { return static_cast<std::uint64_t>(v + kCellCoordLimit) & kMask; };
  return u(x) | (u(y) << kCellKeyFieldBits) | (u(z) << (2 * kCellKeyFieldBits));
}

// The coordinates pack_cell() packed into key (not kEmptyCellKey).
inline void unpack_cell(std::uint64_t key, int& x, int& y, int& z) {
  constexpr std::uint64_t kMask = (std::uint64_t{1} << kCellKeyFieldBits) - 1;
  const auto v = [](std::uint64_t field) { return static_cast<int>(field) - kCellCoordLimit; };
  x = v(key & kMask);
  y = v((key >> kCellKeyFieldBits) & kMask);
  z = v((key >> (2 * kCellKeyFieldBits)) & kMask);
}

// What to add to pack_cell(x, y, z) for the key of (x + dx, y + dy, z + dz), dx, dy, dz in
// {0, 1}, where every coordinate stays within the limits (then no field carries).
inline constexpr std::uint64_t cell_key_step(int dx, int dy, int dz) {
  return static_cast<std::uint64_t>(dx) | (static_cast<std::uint64_t>(dy) << kCellKeyFieldBits) |
         (static_cast<std::uint64_t>(dz) << (2 * kCellKeyFieldBits));
}

// A bit mixer (splitmix64's): packed keys of neighbouring cells differ in low bits only.
inline std::size_t hash_cell_key(std::uint64_t key) {
  key ^= key >> 29;
  key *= 0xbf58476d1ce4e5b9ULL;
  key ^= key >> 32;
  return static_cast<std::size_t>(key);
}

}  // namespace ambisim
