#pragma once
// Colour spaces for display and perceptual metrics: linear sRGB -> CIE XYZ -> CIELAB, the sRGB
// transfer function (OETF) and 8-bit quantisation.
//
// Conventions (fixed project-wide so every Lab value is comparable):
// - linear sRGB = Rec.709 primaries with the D65 white; the RGB -> XYZ matrix is derived from the
//   primaries' chromaticities and the white XYZ below (not the 4-digit IEC table), so linear
//   (1, 1, 1) maps to the white exactly and to Lab (100, 0, 0);
// - reference white D65, 2-degree observer, Y normalised to 1: Xn = 0.95047, Yn = 1, Zn = 1.08883
//   (the values of ASTM E308 / Lindbloom, the most widely used tabulation; CIEDE2000 test data
//   are white-independent, but published sRGB Lab values assume this white);
// - CIELAB uses the exact CIE rationals epsilon = 216/24389 and kappa = 24389/27 rather than the
//   rounded 0.008856 / 903.3, so the piecewise f() is continuous.
#include <cstdint>

#include <glm/vec3.hpp>

namespace ambisim {

// CIELAB colour: L* in [0, 100] for displayable colours, a*, b* roughly in [-128, 128].
struct Lab {
  double L = 0.0;
  double a = 0.0;
  double b = 0.0;

  // Component-wise, so metrics can form P + (R_t - R_{t-1}) in Lab.
  friend Lab operator+(const Lab& p, const Lab& q) { return {p.L + q.L, p.a + q.a, p.b + q.b}; }
  friend Lab operator-(const Lab& p, const Lab& q) { return {p.L - q.L, p.a - q.a, p.b - q.b}; }
  friend bool operator==(const Lab&, const Lab&) = default;
};

inline constexpr double kD65WhiteX = 0.95047;
inline constexpr double kD65WhiteY = 1.0;
inline constexpr double kD65WhiteZ = 1.08883;

// Rows of the linear sRGB -> XYZ matrix, derived from the Rec.709 primaries
// (0.64, 0.33), (0.30, 0.60), (0.15, 0.06) and the white above (exact rational arithmetic,
// rounded to double). Row sums equal the white; the Y row is the luminance weighting.
inline constexpr double kSrgbToXyz[3][3] = {
    {0.4124564390896921, 0.35757607764390897, 0.18043748326639894},
    {0.21267285140562248, 0.71515215528781795, 0.072174993306559576},
    {0.019333895582329317, 0.119192025881303, 0.95030407853636767}};

// Linear sRGB (any real values; [0, 1] is the display gamut) -> XYZ with Y = 1 for white.
glm::dvec3 linear_srgb_to_xyz(const glm::dvec3& rgb);

// Relative luminance Y of a linear sRGB colour (the Y row of kSrgbToXyz).
double srgb_luminance(const glm::dvec3& rgb);

// XYZ (non-negative, Y = 1 for the D65 white) -> CIELAB relative to the D65 white.
Lab xyz_to_lab(const glm::dvec3& xyz);

// Linear sRGB -> CIELAB (D65); inputs are expected in [0, 1] (display-linear).
Lab linear_srgb_to_lab(const glm::dvec3& rgb);

// sRGB OETF (IEC 61966-2-1): display-linear [0, 1] -> encoded [0, 1]. Inputs outside [0, 1] are
// clamped first (the curve is only defined on the display range).
double srgb_encode(double linear);

// Inverse of srgb_encode: encoded [0, 1] -> linear [0, 1]; clamps its input likewise.
double srgb_decode(double encoded);

// Encoded [0, 1] -> 8-bit code, rounding to nearest (clamped, so out-of-range saturates).
std::uint8_t quantise_8bit(double encoded);

}  // namespace ambisim
