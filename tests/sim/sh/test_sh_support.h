#pragma once
// Helpers shared by the SH / cube-map tests: cubes filled from a function of direction,
// a fixed normal set and a seeded hash-based random source.
#include <cstdint>
#include <vector>

#include <glm/geometric.hpp>

#include "sim/sh/cube_map.h"
#include "sim/sh/sh9.h"

namespace ambisim::test {

// Radiance at each texel centre direction.
template <class F>
CubeMap cube_from(int size, F radiance) {
  CubeMap cube(size);
  for (int f = 0; f < kCubeFaces; ++f) {
    const auto face = static_cast<CubeFace>(f);
    for (int j = 0; j < size; ++j) {
      for (int i = 0; i < size; ++i) {
        cube.at(face, i, j) = radiance(cube_texel_direction(face, size, i, j));
      }
    }
  }
  return cube;
}

// The 26 directions to the faces, edges and corners of a cube.
inline std::vector<glm::dvec3> normals26() {
  std::vector<glm::dvec3> out;
  for (int a = -1; a <= 1; ++a)
    for (int b = -1; b <= 1; ++b)
      for (int c = -1; c <= 1; ++c)
        if (a != 0 || b != 0 || c != 0) out.push_back(glm::normalize(glm::dvec3(a, b, c)));
  return out;
}

// splitmix64 keyed by (seed, index): uniform in [lo, hi), independent of call order.
inline double hash_uniform(std::uint64_t seed, std::uint64_t index, double lo, double hi) {
  std::uint64_t z = seed * 0x9E3779B97F4A7C15ull + index + 0x632BE59BD9B4E019ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return lo + (hi - lo) * static_cast<double>(z >> 11) * 0x1.0p-53;
}

// Nine random RGB coefficients in [-1, 1), plus `dc` on the constant term.
inline Sh9Rgb random_sh(std::uint64_t seed, float dc = 0.0f) {
  Sh9Rgb sh;
  for (int k = 0; k < kShCount; ++k) {
    for (int ch = 0; ch < 3; ++ch) {
      sh.c[k][ch] = static_cast<float>(hash_uniform(seed, 3 * k + ch, -1.0, 1.0));
    }
  }
  sh.c[0] += Rgb(dc);
  return sh;
}

// Texel radiance in [0, 10), independent per texel and channel.
inline CubeMap random_cube(int size, std::uint64_t seed) {
  CubeMap cube(size);
  for (std::size_t t = 0; t < cube.texel.size(); ++t) {
    for (int ch = 0; ch < 3; ++ch) {
      cube.texel[t][ch] = static_cast<float>(hash_uniform(seed, 3 * t + ch, 0.0, 10.0));
    }
  }
  return cube;
}

inline double max_abs_diff(const Sh9Rgb& a, const Sh9Rgb& b) {
  double m = 0.0;
  for (int k = 0; k < kShCount; ++k)
    for (int ch = 0; ch < 3; ++ch) m = std::max(m, double(std::abs(a.c[k][ch] - b.c[k][ch])));
  return m;
}

}  // namespace ambisim::test
