#pragma once
// Order-2 (9-coefficient) real spherical harmonics, one set per RGB channel.
//
// Convention (used everywhere, for projection and evaluation alike):
// - coefficient order of Ramamoorthi & Hanrahan 2001: 00, 1-1, 10, 11, 2-2, 2-1, 20, 21, 22;
// - real basis without the Condon-Shortley phase: Y1-1 = k1 y, Y10 = k1 z, Y11 = k1 x;
// - the world frame: x east, y north, z up. Directions are unit vectors in that frame.
#include <array>

#include <glm/vec3.hpp>

#include "sim/colour/rgb.h"

namespace ambisim {

inline constexpr int kShCount = 9;

// Basis normalisation constants (R&H 2001, eq. 3).
inline constexpr double kShY00 = 0.282094791773878143;  // 1 / (2 sqrt(pi))
inline constexpr double kShY1 = 0.488602511902919921;   // sqrt(3 / (4 pi))
inline constexpr double kShY2 = 1.092548430592079070;   // sqrt(15 / (4 pi))
inline constexpr double kShY20 = 0.315391565252520006;  // sqrt(5 / (16 pi))
inline constexpr double kShY22 = 0.546274215296039535;  // sqrt(15 / (16 pi))

// Irradiance constants c1..c5 of R&H 2001, eq. 12.
inline constexpr double kShC1 = 0.429043;
inline constexpr double kShC2 = 0.511664;
inline constexpr double kShC3 = 0.743125;
inline constexpr double kShC4 = 0.886227;
inline constexpr double kShC5 = 0.247708;

// Clamped-cosine kernel per band, A_l = pi, 2 pi / 3, pi / 4 (R&H 2001, eq. 8/9):
// E(n) = sum_lm A_l L_lm Y_lm(n). The c1..c5 above are these times the basis constants,
// rounded to 6 digits; sh_irradiance uses the unrounded products.
inline constexpr double kShA0 = 3.14159265358979323846;
inline constexpr double kShA1 = 2.0 * kShA0 / 3.0;
inline constexpr double kShA2 = kShA0 / 4.0;

// Band l of coefficient k (0 for k = 0, 1 for k = 1..3, 2 for k = 4..8).
constexpr int sh_band(int k) { return k == 0 ? 0 : (k < 4 ? 1 : 2); }

using ShBasis = std::array<double, kShCount>;

// The 9 basis functions at a unit direction. Input must be normalised (|d| = 1 within 1e-6).
ShBasis sh_basis(const glm::dvec3& unit_dir);

// 9 RGB coefficients: the radiance function L(w) ~ sum_k c[k] Y_k(w).
struct Sh9Rgb {
  std::array<Rgb, kShCount> c{};

  // Inline: lookups sum tens of these per call (an out-of-line call and a temporary per term
  // cost a third of a far-field lookup).
  Sh9Rgb& operator+=(const Sh9Rgb& o) {
    for (int k = 0; k < kShCount; ++k)
      c[static_cast<std::size_t>(k)] += o.c[static_cast<std::size_t>(k)];
    return *this;
  }
  Sh9Rgb& operator*=(float s) {
    for (auto& v : c) v *= s;
    return *this;
  }
  friend Sh9Rgb operator+(Sh9Rgb a, const Sh9Rgb& b) { return a += b; }
  friend Sh9Rgb operator*(Sh9Rgb a, float s) { return a *= s; }
  friend Sh9Rgb operator*(float s, Sh9Rgb a) { return a *= s; }
  friend bool operator==(const Sh9Rgb&, const Sh9Rgb&) = default;
};

// acc += w x x, without a temporary (the same float operations as acc += x * w).
inline void sh_add_scaled(Sh9Rgb& acc, const Sh9Rgb& x, float w) {
  for (int k = 0; k < kShCount; ++k) {
    acc.c[static_cast<std::size_t>(k)] += x.c[static_cast<std::size_t>(k)] * w;
  }
}

// a + t (b - a), t in [0, 1].
Sh9Rgb sh_lerp(const Sh9Rgb& a, const Sh9Rgb& b, float t);

// The radiance function itself at a unit direction (used for round trips).
Rgb sh_radiance(const Sh9Rgb& sh, const glm::dvec3& unit_dir);

// Irradiance E(n) at a surface with unit normal n, via the R&H quadratic form (eq. 13).
Rgb sh_irradiance(const Sh9Rgb& sh, const glm::dvec3& unit_normal);

// Keep only the first `bands` bands (1: L0 only, 2: L0+L1 = 4 coefficients, 3: all 9).
Sh9Rgb sh_truncate(const Sh9Rgb& sh, int bands);

}  // namespace ambisim
