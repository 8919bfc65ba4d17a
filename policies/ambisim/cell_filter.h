#pragma once
// A one-hash Bloom filter over a set of cell keys, by their hash_cell_key (cell_key.h), for the
// ambisim planner's spatial index and far field: may_hold(h) is true for every key added and
// false for most others (about one in kBitsPerCell passes).
//
// Why: most cells a lookup asks for are empty (in bench_planners' fill at 1e4 probes, 14 of the
// 16 cells the index reads per point and 8 of the 13 corners the far field reads), and a bit of
// a table sixteen times smaller than the hash table's (2 bytes per cell against 32) answers that
// before the table's probe sequence. The filter reads the hash's top bits and the table its low
// ones, so the two are independent.
//
// Input range: h any value of hash_cell_key; reset() sized for at least the number of keys to be
// added (more keys only raise the false-positive rate).
#include <bit>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace ambisim {

class CellFilter {
 public:
  static constexpr std::size_t kBitsPerCell = 16;

  // Empty, sized for `cells` keys.
  void reset(std::size_t cells) {
    std::size_t words = 1;
    while (64 * words < kBitsPerCell * cells) words *= 2;
    words_.assign(words, 0);
    shift_ = 64 - std::countr_zero(64 * words);
  }
  void add(std::size_t h) {
    const std::size_t b = bit(h);
    words_[b >> 6] |= std::uint64_t{1} << (b & 63);
  }
  // False before the first reset().
  bool may_hold(std::size_t h) const {
    if (words_.empty()) return false;
    const std::size_t b = bit(h);
    return (words_[b >> 6] >> (b & 63)) & 1u;
  }
  std::size_t bytes() const { return words_.capacity() * sizeof(std::uint64_t); }

 private:
  std::size_t bit(std::size_t h) const { return static_cast<std::uint64_t>(h) >> shift_; }

  std::vector<std::uint64_t> words_;
  int shift_ = 64;
};

}  // namespace ambisim
