// CIELAB and sRGB transfer: white point, published primaries, closed forms, breakpoints.
#include <catch2/catch.hpp>
#include <cmath>

#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include "sim/colour/cielab.h"

using ambisim::Lab;

namespace {
// Lab of exactly representable cases (white, closed forms): only double rounding remains.
// Measured: 1.5e-14 (grey 0.18).
constexpr double kLabExactTol = 1e-6;
// Published Lab values are given to 4 decimals.
constexpr double kLabPublishedTol = 1e-3;
// The matrix constants are the exact derivation rounded to double. Measured: 2.2e-16.
constexpr double kMatrixTol = 1e-12;
// sRGB encode/decode are exact inverses up to pow() rounding. Measured: 3.3e-16.
constexpr double kSrgbRoundTripTol = 1e-12;
// The published breakpoints 0.0031308 / 0.04045 agree with each other to 3e-8 only.
constexpr double kSrgbBreakTol = 1e-7;

void check_lab(const Lab& got, const Lab& want, double tol) {
  CHECK(got.L == Approx(want.L).margin(tol));
  CHECK(got.a == Approx(want.a).margin(tol));
  CHECK(got.b == Approx(want.b).margin(tol));
}
}  // namespace

TEST_CASE("sRGB to XYZ matrix is the derivation from Rec.709 primaries and D65", "[colour]") {
  // Oracle: M = [P columns xyz/y] * diag(P^-1 W), computed here with a generic inverse.
  const double xy[3][2] = {{0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06}};
  glm::dmat3 p;  // column c = primary c
  for (int c = 0; c < 3; ++c) {
    p[c] = {xy[c][0] / xy[c][1], 1.0, (1.0 - xy[c][0] - xy[c][1]) / xy[c][1]};
  }
  const glm::dvec3 white(ambisim::kD65WhiteX, ambisim::kD65WhiteY, ambisim::kD65WhiteZ);
  const glm::dvec3 s = glm::inverse(p) * white;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      CHECK(ambisim::kSrgbToXyz[r][c] == Approx(p[c][r] * s[c]).margin(kMatrixTol));
    }
  }
  const glm::dvec3 w = ambisim::linear_srgb_to_xyz({1.0, 1.0, 1.0});
  CHECK(w.x == Approx(ambisim::kD65WhiteX).margin(kMatrixTol));
  CHECK(w.y == Approx(1.0).margin(kMatrixTol));
  CHECK(w.z == Approx(ambisim::kD65WhiteZ).margin(kMatrixTol));
  CHECK(ambisim::srgb_luminance({1.0, 1.0, 1.0}) == Approx(1.0).margin(kMatrixTol));
}

TEST_CASE("Lab of white, greys and black follow the closed forms", "[colour]") {
  check_lab(ambisim::linear_srgb_to_lab({1.0, 1.0, 1.0}), {100.0, 0.0, 0.0}, kLabExactTol);
  check_lab(ambisim::linear_srgb_to_lab({0.0, 0.0, 0.0}), {0.0, 0.0, 0.0}, kLabExactTol);
  // Cube-root branch: L = 116 Y^(1/3) - 16 for a grey of luminance Y = 0.18.
  check_lab(ambisim::linear_srgb_to_lab({0.18, 0.18, 0.18}),
            {116.0 * std::cbrt(0.18) - 16.0, 0.0, 0.0}, kLabExactTol);
  // Linear branch below epsilon = 216/24389 = 0.008856: L = kappa Y, kappa = 24389/27.
  check_lab(ambisim::linear_srgb_to_lab({0.001, 0.001, 0.001}), {24389.0 / 27.0 * 0.001, 0.0, 0.0},
            kLabExactTol);
  // The exact CIE constants make the two branches meet at epsilon (L = 8 there).
  const double eps = 216.0 / 24389.0;
  CHECK(ambisim::xyz_to_lab({eps * ambisim::kD65WhiteX, eps, eps * ambisim::kD65WhiteZ}).L ==
        Approx(8.0).margin(kLabExactTol));
}

TEST_CASE("Lab of the sRGB primaries matches published values (D65)", "[colour]") {
  // Lindbloom's calculator (sRGB, D65, matrix derived from primaries); reproduced independently
  // with exact rational arithmetic: red (53.240789, 80.092494, 67.203191), green
  // (87.734720, -86.182715, 83.179310), blue (32.297009, 79.187517, -107.860163).
  // (The often-quoted blue L* = 32.3026 comes from the 4-digit IEC matrix, not this white.)
  check_lab(ambisim::linear_srgb_to_lab({1.0, 0.0, 0.0}), {53.2408, 80.0925, 67.2032},
            kLabPublishedTol);
  check_lab(ambisim::linear_srgb_to_lab({0.0, 1.0, 0.0}), {87.7347, -86.1827, 83.1793},
            kLabPublishedTol);
  check_lab(ambisim::linear_srgb_to_lab({0.0, 0.0, 1.0}), {32.2970, 79.1875, -107.8602},
            kLabPublishedTol);
}

TEST_CASE("Lab arithmetic is component-wise", "[colour]") {
  const Lab p{50.0, 10.0, -20.0}, r0{40.0, 1.0, 2.0}, r1{45.0, -3.0, 2.5};
  const Lab q = p + (r1 - r0);
  CHECK(q == Lab{55.0, 6.0, -19.5});
}

TEST_CASE("sRGB transfer: breakpoints, round trip, known codes", "[colour]") {
  // IEC 61966-2-1 breakpoints: 0.0031308 linear <-> 0.04045 encoded, 12.92 slope below.
  CHECK(ambisim::srgb_encode(0.0031308) == Approx(0.04045).margin(kSrgbBreakTol));
  CHECK(ambisim::srgb_decode(0.04045) == Approx(0.0031308).margin(kSrgbBreakTol));
  // The two pieces nearly meet at the break (3e-8 apart by the standard's rounding).
  const double above = 1.055 * std::pow(0.0031308, 1.0 / 2.4) - 0.055;
  CHECK(above == Approx(0.0031308 * 12.92).margin(kSrgbBreakTol));
  CHECK(ambisim::srgb_encode(0.001) == Approx(0.01292).margin(kSrgbRoundTripTol));
  CHECK(ambisim::srgb_encode(1.0) == Approx(1.0).margin(kSrgbRoundTripTol));
  CHECK(ambisim::srgb_encode(0.0) == 0.0);
  CHECK(ambisim::srgb_encode(2.0) == Approx(1.0).margin(kSrgbRoundTripTol));  // clamped
  for (int k = 0; k <= 1000; ++k) {
    const double x = k / 1000.0;
    CHECK(ambisim::srgb_decode(ambisim::srgb_encode(x)) == Approx(x).margin(kSrgbRoundTripTol));
    CHECK(ambisim::srgb_encode(ambisim::srgb_decode(x)) == Approx(x).margin(kSrgbRoundTripTol));
  }
  // Well-known codes: linear 0.5 -> 188, middle grey 0.18 -> 118 (0.7354 and 0.4614 encoded).
  CHECK(ambisim::quantise_8bit(ambisim::srgb_encode(0.5)) == 188);
  CHECK(ambisim::quantise_8bit(ambisim::srgb_encode(0.18)) == 118);
}

TEST_CASE("8-bit quantisation rounds to nearest and saturates", "[colour]") {
  CHECK(ambisim::quantise_8bit(0.0) == 0);
  CHECK(ambisim::quantise_8bit(1.0) == 255);
  CHECK(ambisim::quantise_8bit(127.4 / 255.0) == 127);
  CHECK(ambisim::quantise_8bit(127.6 / 255.0) == 128);
  CHECK(ambisim::quantise_8bit(-0.3) == 0);
  CHECK(ambisim::quantise_8bit(7.0) == 255);
  CHECK(ambisim::quantise_8bit(std::nan("")) == 0);
  for (int k = 0; k <= 255; ++k) CHECK(ambisim::quantise_8bit(k / 255.0) == k);
}
