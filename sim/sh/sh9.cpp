#include "sim/sh/sh9.h"

#include <cmath>

namespace ambisim {
namespace {

// Unrounded R&H irradiance constants (A_l times basis constants). The published 6-digit
// values are off by up to 1.1e-6 (c3 = 0.7431239, c2 = 0.5116634), which would bias every
// irradiance by ~1e-6 relative; these agree with them to that.
constexpr double kC1 = kShA2 * kShY22;        // 0.429043
constexpr double kC2 = kShA1 * kShY1 / 2.0;   // 0.511664
constexpr double kC3 = 3.0 * kShA2 * kShY20;  // 0.743125
constexpr double kC4 = kShA0 * kShY00;        // 0.886227
constexpr double kC5 = kShA2 * kShY20;        // 0.247708

constexpr bool near6(double a, double b) { return (a - b) < 2e-6 && (b - a) < 2e-6; }
static_assert(near6(kC1, kShC1) && near6(kC2, kShC2) && near6(kC3, kShC3) && near6(kC4, kShC4) &&
              near6(kC5, kShC5));

}  // namespace

ShBasis sh_basis(const glm::dvec3& d) {
  const double x = d.x, y = d.y, z = d.z;
  return {kShY00,
          kShY1 * y,
          kShY1 * z,
          kShY1 * x,
          kShY2 * x * y,
          kShY2 * y * z,
          kShY20 * (3.0 * z * z - 1.0),
          kShY2 * x * z,
          kShY22 * (x * x - y * y)};
}

Sh9Rgb sh_lerp(const Sh9Rgb& a, const Sh9Rgb& b, float t) {
  Sh9Rgb r;
  for (int k = 0; k < kShCount; ++k) r.c[k] = a.c[k] + t * (b.c[k] - a.c[k]);
  return r;
}

Rgb sh_radiance(const Sh9Rgb& sh, const glm::dvec3& unit_dir) {
  const ShBasis y = sh_basis(unit_dir);
  glm::dvec3 sum(0.0);
  for (int k = 0; k < kShCount; ++k) sum += glm::dvec3(sh.c[k]) * y[k];
  return Rgb(sum);
}

Rgb sh_irradiance(const Sh9Rgb& sh, const glm::dvec3& n) {
  const double x = n.x, y = n.y, z = n.z;
  auto L = [&](int k) { return glm::dvec3(sh.c[k]); };
  // R&H 2001 eq. 13, coefficient order 00, 1-1, 10, 11, 2-2, 2-1, 20, 21, 22.
  const glm::dvec3 e = kC1 * L(8) * (x * x - y * y) + kC3 * L(6) * (z * z) + kC4 * L(0) -
                       kC5 * L(6) + 2.0 * kC1 * (L(4) * (x * y) + L(7) * (x * z) + L(5) * (y * z)) +
                       2.0 * kC2 * (L(3) * x + L(1) * y + L(2) * z);
  return Rgb(e);
}

Sh9Rgb sh_truncate(const Sh9Rgb& sh, int bands) {
  Sh9Rgb r = sh;
  for (int k = 0; k < kShCount; ++k) {
    if (sh_band(k) >= bands) r.c[k] = Rgb(0.0f);
  }
  return r;
}

}  // namespace ambisim
