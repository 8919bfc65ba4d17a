#pragma once
// The clear sky and the sun through it, in photometric units: sky radiance in kcd/m^2 (the
// Preetham model's unit), sun irradiance in klx, as linear sRGB (Y = 0.2126 R + 0.7152 G +
// 0.0722 B is the luminance).
// - PreethamSky: Preetham, Shirley & Smits 1999, "A Practical Analytic Model for Daylight":
//   the Perez et al. distribution F(theta, gamma) = (1 + A e^{B / cos theta})
//   (1 + C e^{D gamma} + E cos^2 gamma) for Y, x and y with the paper's coefficients (linear in
//   the turbidity T), its zenith luminance Y_z = (4.0453 T - 4.9710) tan chi - 0.2155 T + 2.4192,
//   chi = (4/9 - T/120)(pi - 2 theta_s), and its zenith chromaticity polynomials; then xyY ->
//   XYZ -> linear sRGB (D65). Valid for the sun above the horizon and T in [2, 10] (it breaks
//   below T = 1.64 and, near the horizon, above T = 11.2); view directions below the horizon
//   take the horizon's value.
// - sun_irradiance: the extraterrestrial sun (127 klx, x 0.317, y 0.326) attenuated per RGB
//   channel (680, 550, 440 nm) by Rayleigh scattering exp(-m 0.008735 lambda^-4.08), aerosols
//   (Angstrom: beta = 0.04608 T - 0.04586, alpha 1.3) and ozone (0.35 cm) over the Kasten-Young
//   air mass m: Preetham's appendix at three wavelengths, which reddens and dims the sun toward
//   the horizon.
// - twilight_factor: below the horizon the sky fades as the global illuminance of USNO Circular
//   171 (Janiczek & DeYoung 1987) does, relative to its value at sunset (2.99 lux at -6 deg,
//   0.0044 at -12 deg), floored at the night sky's airglow and starlight (0.002 lux).
#include <glm/vec3.hpp>

#include "sim/colour/rgb.h"

namespace ambisim {

class PreethamSky {
 public:
  // turbidity in [1.7, 10]; sun_dir unit toward the sun (its z clamped to >= 0: a sun below the
  // horizon is evaluated at the horizon).
  PreethamSky(double turbidity, const glm::dvec3& sun_dir);

  // Radiance (kcd/m^2, linear sRGB) toward unit d.
  Rgb radiance(const glm::dvec3& d) const;
  // The model's zenith luminance Y_z and chromaticity.
  double zenith_luminance() const { return yz_[0]; }
  double zenith_x() const { return yz_[1]; }
  double zenith_y() const { return yz_[2]; }
  // The model's (Y, x, y) toward d.
  glm::dvec3 xyY(const glm::dvec3& d) const;

  // Perez coefficients A..E of channel c (0 Y, 1 x, 2 y) at turbidity T (for tests).
  static void perez_coefficients(double turbidity, int channel, double out[5]);
  static double zenith_luminance(double turbidity, double sun_zenith_rad);
  static double zenith_chromaticity(double turbidity, double sun_zenith_rad, int channel);

 private:
  double coef_[3][5];
  double yz_[3];    // zenith Y, x, y
  double norm_[3];  // F(0, theta_s) per channel
  glm::dvec3 sun_{0.0, 0.0, 1.0};
  double theta_s_ = 0.0;
};

// Linear sRGB (D65) of a CIE xyY colour.
Rgb xyY_to_linear_srgb(double x, double y, double Y);

// Sun irradiance on a plane facing it (klx, RGB) at an apparent elevation (deg), turbidity T;
// 0 at or below the horizon.
Rgb sun_irradiance(double apparent_elevation_deg, double turbidity);

// The sky's brightness below the horizon relative to sunset (1 at elevation >= 0; decreasing).
double twilight_factor(double elevation_deg);

// USNO Circular 171's clear-sky global (sun + sky) horizontal illuminance in lux at a true
// solar altitude h (deg): 133775 M(h), the formula twilight_factor follows.
double usno_global_illuminance_lux(double altitude_deg);

}  // namespace ambisim
