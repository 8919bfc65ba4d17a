#include "sim/colour/cielab.h"

#include <algorithm>
#include <cmath>

namespace ambisim {
namespace {

// CIE 1976 constants as exact rationals (CIE 15:2004 note): epsilon = (6/29)^3,
// kappa = (29/3)^3.
constexpr double kLabEpsilon = 216.0 / 24389.0;
constexpr double kLabKappa = 24389.0 / 27.0;

double lab_f(double t) { return t > kLabEpsilon ? std::cbrt(t) : (kLabKappa * t + 16.0) / 116.0; }

// sRGB transfer constants; the breakpoints 0.0031308 (linear) and 0.04045 (encoded) are the
// published ones and meet to within 1e-8 (the curve is not exactly continuous by design).
constexpr double kSrgbLinearBreak = 0.0031308;
constexpr double kSrgbEncodedBreak = 0.04045;

}  // namespace

glm::dvec3 linear_srgb_to_xyz(const glm::dvec3& rgb) {
  glm::dvec3 xyz;
  for (int r = 0; r < 3; ++r) {
    xyz[r] = kSrgbToXyz[r][0] * rgb.x + kSrgbToXyz[r][1] * rgb.y + kSrgbToXyz[r][2] * rgb.z;
  }
  return xyz;
}

double srgb_luminance(const glm::dvec3& rgb) {
  return kSrgbToXyz[1][0] * rgb.x + kSrgbToXyz[1][1] * rgb.y + kSrgbToXyz[1][2] * rgb.z;
}

Lab xyz_to_lab(const glm::dvec3& xyz) {
  const double fx = lab_f(xyz.x / kD65WhiteX);
  const double fy = lab_f(xyz.y / kD65WhiteY);
  const double fz = lab_f(xyz.z / kD65WhiteZ);
  return {116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

Lab linear_srgb_to_lab(const glm::dvec3& rgb) { return xyz_to_lab(linear_srgb_to_xyz(rgb)); }

double srgb_encode(double linear) {
  const double x = std::clamp(linear, 0.0, 1.0);
  return x <= kSrgbLinearBreak ? 12.92 * x : 1.055 * std::pow(x, 1.0 / 2.4) - 0.055;
}

double srgb_decode(double encoded) {
  const double y = std::clamp(encoded, 0.0, 1.0);
  return y <= kSrgbEncodedBreak ? y / 12.92 : std::pow((y + 0.055) / 1.055, 2.4);
}

std::uint8_t quantise_8bit(double encoded) {
  // NaN (e.g. from a degenerate upstream value) must not reach the cast: treat it as black.
  if (!(encoded > 0.0)) return 0;
  // +0.5 then truncate == round half up; the value is non-negative here.
  return static_cast<std::uint8_t>(std::min(encoded, 1.0) * 255.0 + 0.5);
}

}  // namespace ambisim
