// SH basis values, orthonormality, the R&H irradiance quadratic form and the Sh9Rgb ops.
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "sim/sh/cube_map.h"
#include "sim/sh/sh9.h"
#include "test_sh_support.h"

using namespace ambisim;

namespace {

constexpr double kBasisValueTol = 1e-12;
// Gram matrix by the texel-centre rule with exact solid angles: measured max |G - I| =
// 1.6e-3 at N = 16 and 9.9e-5 at N = 64 (second order in the texel size).
constexpr double kGramTol64 = 2e-4;
// Float coefficients against a double-precision alternative formula: measured <= 5e-7.
constexpr double kIrradianceFormTol = 2e-6;

}  // namespace

TEST_CASE("SH basis matches hand-computed values", "[sh]") {
  const double k1 = std::sqrt(3.0 / (4.0 * std::numbers::pi));
  const double k2 = std::sqrt(15.0 / (4.0 * std::numbers::pi));
  const double k20 = std::sqrt(5.0 / (16.0 * std::numbers::pi));
  const double k22 = std::sqrt(15.0 / (16.0 * std::numbers::pi));
  const double y00 = 0.5 / std::sqrt(std::numbers::pi);
  auto check = [](const ShBasis& got, const ShBasis& want) {
    for (int k = 0; k < kShCount; ++k) {
      INFO("k = " << k);
      CHECK(got[k] == Approx(want[k]).margin(kBasisValueTol));
    }
  };
  // Order 00, 1-1 (y), 10 (z), 11 (x), 2-2 (xy), 2-1 (yz), 20, 21 (xz), 22 (x^2 - y^2).
  check(sh_basis({0, 0, 1}), {y00, 0, k1, 0, 0, 0, 2 * k20, 0, 0});
  check(sh_basis({1, 0, 0}), {y00, 0, 0, k1, 0, 0, -k20, 0, k22});
  check(sh_basis({0, 1, 0}), {y00, k1, 0, 0, 0, 0, -k20, 0, -k22});
  check(sh_basis({0, -1, 0}), {y00, -k1, 0, 0, 0, 0, -k20, 0, -k22});  // no Condon-Shortley
  const double s = 1.0 / std::sqrt(3.0);
  check(sh_basis({s, s, s}), {y00, k1 * s, k1 * s, k1 * s, k2 / 3, k2 / 3, 0, k2 / 3, 0});
  const double r = 1.0 / std::sqrt(2.0);
  check(sh_basis({r, -r, 0}), {y00, -k1 * r, 0, k1 * r, -k2 / 2, 0, -k20, 0, 0});
  // The header constants are the closed forms.
  CHECK(kShY1 == Approx(k1).epsilon(1e-15));
  CHECK(kShY2 == Approx(k2).epsilon(1e-15));
  CHECK(kShY20 == Approx(k20).epsilon(1e-15));
  CHECK(kShY22 == Approx(k22).epsilon(1e-15));
  CHECK(kShY00 == Approx(y00).epsilon(1e-15));
}

TEST_CASE("SH basis is orthonormal under cube quadrature", "[sh]") {
  const int n = 64;
  std::array<std::array<double, kShCount>, kShCount> gram{};
  for (int f = 0; f < kCubeFaces; ++f) {
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        const ShBasis y = sh_basis(cube_texel_direction(static_cast<CubeFace>(f), n, i, j));
        const double w = cube_texel_solid_angle(n, i, j);
        for (int a = 0; a < kShCount; ++a)
          for (int b = 0; b < kShCount; ++b) gram[a][b] += w * y[a] * y[b];
      }
    }
  }
  for (int a = 0; a < kShCount; ++a) {
    for (int b = 0; b < kShCount; ++b) {
      INFO("G(" << a << "," << b << ")");
      CHECK(std::abs(gram[a][b] - (a == b ? 1.0 : 0.0)) < kGramTol64);
    }
  }
}

TEST_CASE("sh_irradiance is the clamped-cosine convolution sum A_l L_lm Y_lm(n)", "[sh]") {
  // Independent form: A_0 = pi, A_1 = 2 pi / 3, A_2 = pi / 4 times the basis at n.
  const std::array<double, 3> a = {std::numbers::pi, 2.0 * std::numbers::pi / 3.0,
                                   std::numbers::pi / 4.0};
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    const Sh9Rgb sh = test::random_sh(seed);
    for (const glm::dvec3& n : test::normals26()) {
      const ShBasis y = sh_basis(n);
      glm::dvec3 want(0.0);
      for (int k = 0; k < kShCount; ++k) want += a[sh_band(k)] * y[k] * glm::dvec3(sh.c[k]);
      const Rgb got = sh_irradiance(sh, n);
      for (int ch = 0; ch < 3; ++ch) CHECK(std::abs(got[ch] - want[ch]) < kIrradianceFormTol);
      // And sh_radiance is the plain expansion.
      glm::dvec3 rad(0.0);
      for (int k = 0; k < kShCount; ++k) rad += y[k] * glm::dvec3(sh.c[k]);
      const Rgb got_rad = sh_radiance(sh, n);
      for (int ch = 0; ch < 3; ++ch) CHECK(std::abs(got_rad[ch] - rad[ch]) < kIrradianceFormTol);
    }
  }
}

TEST_CASE("Sh9Rgb arithmetic, lerp and truncation", "[sh]") {
  const Sh9Rgb a = test::random_sh(11), b = test::random_sh(12);
  const Sh9Rgb sum = a + b;
  const Sh9Rgb twice = a * 2.0f;
  const Sh9Rgb twice_left = 2.0f * a;
  for (int k = 0; k < kShCount; ++k) {
    CHECK(sum.c[k] == a.c[k] + b.c[k]);
    CHECK(twice.c[k] == a.c[k] * 2.0f);
    CHECK(twice_left.c[k] == twice.c[k]);
  }
  CHECK(sh_lerp(a, b, 0.0f) == a);
  CHECK(test::max_abs_diff(sh_lerp(a, b, 1.0f), b) < 1e-6);
  const Sh9Rgb mid = sh_lerp(a, b, 0.25f);
  for (int k = 0; k < kShCount; ++k)
    for (int ch = 0; ch < 3; ++ch)
      CHECK(mid.c[k][ch] == Approx(0.75 * a.c[k][ch] + 0.25 * b.c[k][ch]).margin(1e-6));

  const std::array<int, kShCount> band = {0, 1, 1, 1, 2, 2, 2, 2, 2};
  for (int bands = 1; bands <= 3; ++bands) {
    const Sh9Rgb t = sh_truncate(a, bands);
    for (int k = 0; k < kShCount; ++k) {
      CHECK(sh_band(k) == band[k]);
      CHECK(t.c[k] == (band[k] < bands ? a.c[k] : Rgb(0.0f)));
    }
  }
}
