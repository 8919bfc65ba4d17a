#include "sim/sh/sh_projection.h"

#include <cmath>
#include <cstring>
#include <map>
#include <memory>
#include <mutex>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>

#include <glm/geometric.hpp>

namespace ambisim {
namespace {

constexpr int kClassEvenEven = 0, kClassOddU = 1, kClassOddV = 2, kClassOddOdd = 3;
constexpr std::array<int, 4> kClassFirstSlot = {0, 4, 6, 8};
constexpr std::array<int, 4> kClassSlots = {4, 2, 2, 1};

// Parity class of Y_k on a face: Y_k(-u, v) = +-Y_k(u, v) and Y_k(u, -v) = +-Y_k(u, v) hold
// exactly for degree <= 2 monomials of the face directions; read the signs at a generic point.
int parity_class(CubeFace face, int k) {
  const double u = 0.3, v = 0.7;
  auto y = [&](double uu, double vv) {
    return sh_basis(glm::normalize(cube_face_direction(face, uu, vv)))[k];
  };
  const double y0 = y(u, v);
  const bool odd_u = std::abs(y(-u, v) + y0) < 1e-12;
  const bool odd_v = std::abs(y(u, -v) + y0) < 1e-12;
  const bool even_u = std::abs(y(-u, v) - y0) < 1e-12;
  const bool even_v = std::abs(y(u, -v) - y0) < 1e-12;
  if (odd_u == even_u || odd_v == even_v) throw std::logic_error("SH basis has no face parity");
  return odd_u ? (odd_v ? kClassOddOdd : kClassOddU) : (odd_v ? kClassOddV : kClassEvenEven);
}

using V4 = float __attribute__((vector_size(16)));

// Four floats from p: its rgb plus the following float, which must exist.
V4 load4(const Rgb* p) {
  V4 v;
  std::memcpy(&v, p, sizeof(v));
  return v;
}

// rgb and a zero: safe at the end of the texel array.
V4 load3(const Rgb* p) { return V4{p->x, p->y, p->z, 0.0f}; }

}  // namespace

double texel_weight(int size, int i, int j, TexelWeighting weighting) {
  if (weighting == TexelWeighting::uniform_thesis) {
    return 4.0 * std::numbers::pi / (6.0 * size * size);
  }
  return cube_texel_solid_angle(size, i, j);
}

Sh9Rgb project_cube_naive(const CubeMap& cube, TexelWeighting weighting) {
  const int n = cube.size;
  if (n < 1 || cube.texel.size() != static_cast<std::size_t>(kCubeFaces) * n * n) {
    throw std::invalid_argument("project_cube_naive: malformed cube map");
  }
  std::array<glm::dvec3, kShCount> acc{};
  for (int f = 0; f < kCubeFaces; ++f) {
    const auto face = static_cast<CubeFace>(f);
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        const glm::dvec3 dir = glm::normalize(cube_texel_direction(face, n, i, j));
        const ShBasis y = sh_basis(dir);
        const glm::dvec3 lw = glm::dvec3(cube.at(face, i, j)) * texel_weight(n, i, j, weighting);
        for (int k = 0; k < kShCount; ++k) acc[k] += lw * y[k];
      }
    }
  }
  Sh9Rgb out;
  for (int k = 0; k < kShCount; ++k) out.c[k] = Rgb(acc[k]);
  return out;
}

ShProjector::ShProjector(int face_size, TexelWeighting weighting)
    : size_(face_size), weighting_(weighting) {
  if (face_size < 1) throw std::invalid_argument("ShProjector: face_size must be >= 1");
  const int n = size_;
  if (n % 2 == 0) {
    const int h = n / 2;
    folded_.resize(static_cast<std::size_t>(kCubeFaces) * h * h * kShCount);
    for (int f = 0; f < kCubeFaces; ++f) {
      const auto face = static_cast<CubeFace>(f);
      std::array<int, kShCount> slot_of_k{};
      std::array<int, 4> used{};
      for (int k = 0; k < kShCount; ++k) {
        const int c = parity_class(face, k);
        if (used[c] == kClassSlots[c]) throw std::logic_error("unexpected SH parity counts");
        slot_of_k[k] = kClassFirstSlot[c] + used[c]++;
        slot_to_k_[f][slot_of_k[k]] = k;
      }
      // The representative of each mirror quad is its texel with u > 0 and v > 0.
      float* row = folded_.data() + static_cast<std::size_t>(f) * h * h * kShCount;
      for (int j = 0; j < h; ++j) {
        for (int i = 0; i < h; ++i, row += kShCount) {
          const int ri = n - 1 - i, rj = n - 1 - j;
          const ShBasis y = sh_basis(cube_texel_direction(face, n, ri, rj));
          const double w = texel_weight(n, ri, rj, weighting);
          for (int k = 0; k < kShCount; ++k) row[slot_of_k[k]] = static_cast<float>(w * y[k]);
        }
      }
    }
  } else {
    dense_.resize(static_cast<std::size_t>(kCubeFaces) * n * n * kShCount);
    float* row = dense_.data();
    for (int f = 0; f < kCubeFaces; ++f) {
      const auto face = static_cast<CubeFace>(f);
      for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i, row += kShCount) {
          const ShBasis y = sh_basis(cube_texel_direction(face, n, i, j));
          const double w = texel_weight(n, i, j, weighting);
          for (int k = 0; k < kShCount; ++k) row[k] = static_cast<float>(w * y[k]);
        }
      }
    }
  }
}

void ShProjector::check(const CubeMap& cube) const {
  if (cube.size != size_ ||
      cube.texel.size() != static_cast<std::size_t>(kCubeFaces) * size_ * size_) {
    throw std::invalid_argument("ShProjector: cube size " + std::to_string(cube.size) +
                                " does not match projector size " + std::to_string(size_));
  }
}

void ShProjector::accumulate_face(const CubeMap& cube, CubeFace face, Sh9Rgb& acc) const {
  check(cube);
  const int n = size_;
  const int f = static_cast<int>(face);
  const Rgb* tex = &cube.at(face, 0, 0);
  if (n % 2 == 0) {
    const int h = n / 2;
    const float* w = folded_.data() + static_cast<std::size_t>(f) * h * h * kShCount;
    // 4-lane float vectors (GCC/Clang vector extension: plain SSE2 on x86-64, NEON on ARM);
    // lane 3 carries the next texel's red and is discarded.
    std::array<V4, kShCount> s{};
    for (int j = 0; j < h; ++j) {
      const Rgb* lo = tex + static_cast<std::ptrdiff_t>(j) * n;          // v < 0
      const Rgb* hi = tex + static_cast<std::ptrdiff_t>(n - 1 - j) * n;  // v > 0
      for (int i = 0; i < h; ++i, w += kShCount) {
        const V4 a = load4(lo + i), b = load4(lo + (n - 1 - i)), c = load4(hi + i);
        // The face's last texel may be the last of the whole cube: no 4th float after it.
        const V4 d = (i == 0) ? load3(hi + (n - 1)) : load4(hi + (n - 1 - i));
        const V4 p = a + b, q = c + d, r = b - a, t = d - c;
        const V4 ee = p + q, ou = r + t, ov = q - p, oo = t - r;
        s[0] += w[0] * ee;
        s[1] += w[1] * ee;
        s[2] += w[2] * ee;
        s[3] += w[3] * ee;
        s[4] += w[4] * ou;
        s[5] += w[5] * ou;
        s[6] += w[6] * ov;
        s[7] += w[7] * ov;
        s[8] += w[8] * oo;
      }
    }
    for (int slot = 0; slot < kShCount; ++slot) {
      acc.c[slot_to_k_[f][slot]] += Rgb(s[slot][0], s[slot][1], s[slot][2]);
    }
  } else {
    // Odd sizes have a centre row and column that do not fold; one table row per texel.
    const std::size_t t = static_cast<std::size_t>(n) * n;
    const float* w = dense_.data() + static_cast<std::size_t>(f) * t * kShCount;
    std::array<V4, kShCount> s{};
    for (std::size_t e = 0; e < t; ++e, w += kShCount) {
      const V4 l = (e + 1 < t) ? load4(tex + e) : load3(tex + e);
      for (int k = 0; k < kShCount; ++k) s[k] += w[k] * l;
    }
    for (int k = 0; k < kShCount; ++k) acc.c[k] += Rgb(s[k][0], s[k][1], s[k][2]);
  }
}

Sh9Rgb ShProjector::project(const CubeMap& cube) const {
  Sh9Rgb acc;
  for (int f = 0; f < kCubeFaces; ++f) accumulate_face(cube, static_cast<CubeFace>(f), acc);
  return acc;
}

const ShProjector& projector_for(int face_size, TexelWeighting weighting) {
  static std::mutex mutex;
  static std::map<std::pair<int, TexelWeighting>, std::unique_ptr<const ShProjector>> cache;
  const std::lock_guard<std::mutex> lock(mutex);
  auto& slot = cache[{face_size, weighting}];
  if (!slot) slot = std::make_unique<const ShProjector>(face_size, weighting);
  return *slot;
}

}  // namespace ambisim
