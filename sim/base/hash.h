#pragma once
// Integer hashing for procedural content and content fingerprints. Hash-based noise (rather
// than a stateful generator) keeps every generated value independent of evaluation order.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

namespace ambisim {

// SplitMix64 finaliser: a bijective avalanche of all 64 bits.
constexpr std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

constexpr std::uint64_t hash_combine(std::uint64_t h, std::uint64_t v) {
  return splitmix64(h ^ (v + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2)));
}

// Hash of a seed and two lattice coordinates, mapped to [0, 1) with 53 random bits. One
// SplitMix64 round over a linear combination: the noise hot path calls this 4x per octave.
inline double hash_unit(std::uint64_t seed, std::int64_t a, std::int64_t b) {
  const std::uint64_t h = splitmix64(seed + static_cast<std::uint64_t>(a) * 0xD6E8FEB86659FD93ull +
                                     static_cast<std::uint64_t>(b) * 0xC2B2AE3D27D4EB4Full);
  return static_cast<double>(h >> 11) * (1.0 / 9007199254740992.0);
}

// FNV-1a-style streaming fingerprint over raw bytes, mixed per 8-byte word for speed.
class ContentHasher {
 public:
  void add_bytes(const void* data, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    std::size_t k = 0;
    for (; k + 8 <= n; k += 8) {
      std::uint64_t w;
      std::memcpy(&w, p + k, 8);
      h_ = (h_ ^ w) * 0x100000001B3ull;
      h_ ^= h_ >> 29;
    }
    for (; k < n; ++k) h_ = (h_ ^ p[k]) * 0x100000001B3ull;
    h_ = splitmix64(h_ ^ n);
  }
  template <class T>
  void add_vector(const std::vector<T>& v) {
    add_bytes(v.data(), v.size() * sizeof(T));
  }
  template <class T>
  void add_value(const T& v) {
    add_bytes(&v, sizeof(T));
  }
  std::uint64_t value() const { return h_; }

 private:
  std::uint64_t h_ = 0xCBF29CE484222325ull;
};

}  // namespace ambisim
