#include "sim/world/sky_model.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

#include "sim/world/solar_position.h"

namespace ambisim {
namespace {

// Preetham 1999, appendix: [A..E] = M [T, 1] per channel (Y, x, y), the paper's 4 decimals.
constexpr double kPerez[3][5][2] = {
    {{0.1787, -1.4630}, {-0.3554, 0.4275}, {-0.0227, 5.3251}, {0.1206, -2.5771}, {-0.0670, 0.3703}},
    {{-0.0193, -0.2592},
     {-0.0665, 0.0008},
     {-0.0004, 0.2125},
     {-0.0641, -0.8989},
     {-0.0033, 0.0452}},
    {{-0.0167, -0.2608},
     {-0.0950, 0.0092},
     {-0.0079, 0.2102},
     {-0.0441, -1.6537},
     {-0.0109, 0.0529}}};

// Zenith chromaticity: c_z = [T^2 T 1] M [theta^3 theta^2 theta 1]^T (theta_s in radians).
constexpr double kZenithX[3][4] = {{0.00166, -0.00375, 0.00209, 0.0},
                                   {-0.02903, 0.06377, -0.03202, 0.00394},
                                   {0.11693, -0.21196, 0.06052, 0.25886}};
constexpr double kZenithY[3][4] = {{0.00275, -0.00610, 0.00317, 0.0},
                                   {-0.04214, 0.08970, -0.04153, 0.00516},
                                   {0.15346, -0.26756, 0.06670, 0.26688}};

// The horizon limit of view directions (Smits' and Mitsuba's clamp): cos theta >= 0.001.
constexpr double kMinCos = 0.001;

double perez(const double c[5], double cos_theta, double gamma) {
  const double cg = std::cos(gamma);
  return (1.0 + c[0] * std::exp(c[1] / cos_theta)) *
         (1.0 + c[2] * std::exp(c[3] * gamma) + c[4] * cg * cg);
}

}  // namespace

void PreethamSky::perez_coefficients(double t, int channel, double out[5]) {
  for (int k = 0; k < 5; ++k) out[k] = kPerez[channel][k][0] * t + kPerez[channel][k][1];
}

double PreethamSky::zenith_luminance(double t, double theta_s) {
  const double chi = (4.0 / 9.0 - t / 120.0) * (std::numbers::pi - 2.0 * theta_s);
  return (4.0453 * t - 4.9710) * std::tan(chi) - 0.2155 * t + 2.4192;
}

double PreethamSky::zenith_chromaticity(double t, double theta_s, int channel) {
  const auto& m = channel == 1 ? kZenithX : kZenithY;
  const double tv[3] = {t * t, t, 1.0};
  const double sv[4] = {theta_s * theta_s * theta_s, theta_s * theta_s, theta_s, 1.0};
  double c = 0.0;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 4; ++j) c += tv[i] * m[i][j] * sv[j];
  }
  return c;
}

PreethamSky::PreethamSky(double turbidity, const glm::dvec3& sun_dir) {
  sun_ = sun_dir;
  sun_.z = std::max(sun_.z, 0.0);
  const double len = glm::length(sun_);
  sun_ = len > 0.0 ? sun_ / len : glm::dvec3(0.0, 0.0, 1.0);
  theta_s_ = std::acos(std::clamp(sun_.z, 0.0, 1.0));
  for (int c = 0; c < 3; ++c) perez_coefficients(turbidity, c, coef_[c]);
  yz_[0] = zenith_luminance(turbidity, theta_s_);
  yz_[1] = zenith_chromaticity(turbidity, theta_s_, 1);
  yz_[2] = zenith_chromaticity(turbidity, theta_s_, 2);
  for (int c = 0; c < 3; ++c) norm_[c] = perez(coef_[c], 1.0, theta_s_);
}

glm::dvec3 PreethamSky::xyY(const glm::dvec3& d) const {
  const double cos_theta = std::max(d.z, kMinCos);
  // The view direction at the horizon limit keeps its azimuth.
  glm::dvec3 v = d;
  if (d.z < kMinCos) {
    const double h = std::hypot(d.x, d.y);
    const double s = std::sqrt(1.0 - kMinCos * kMinCos);
    v = h > 0.0 ? glm::dvec3(d.x / h * s, d.y / h * s, kMinCos) : glm::dvec3(s, 0.0, kMinCos);
  }
  const double gamma = std::acos(std::clamp(glm::dot(v, sun_), -1.0, 1.0));
  glm::dvec3 out;
  for (int c = 0; c < 3; ++c) out[c] = yz_[c] * perez(coef_[c], cos_theta, gamma) / norm_[c];
  return {out[1], out[2], out[0]};  // x, y, Y
}

Rgb PreethamSky::radiance(const glm::dvec3& d) const {
  const glm::dvec3 c = xyY(d);
  return xyY_to_linear_srgb(c.x, c.y, std::max(c.z, 0.0));
}

Rgb xyY_to_linear_srgb(double x, double y, double Y) {
  if (!(y > 0.0) || !(Y > 0.0)) return Rgb(0.0f);
  const double X = x * Y / y, Z = (1.0 - x - y) * Y / y;
  const double r = 3.2404542 * X - 1.5371385 * Y - 0.4985314 * Z;
  const double g = -0.9692660 * X + 1.8760108 * Y + 0.0415560 * Z;
  const double b = 0.0556434 * X - 0.2040259 * Y + 1.0572252 * Z;
  // Out-of-gamut components (a low sun's deep orange) clamp at 0.
  return Rgb(static_cast<float>(std::max(r, 0.0)), static_cast<float>(std::max(g, 0.0)),
             static_cast<float>(std::max(b, 0.0)));
}

Rgb sun_irradiance(double apparent_elevation_deg, double turbidity) {
  if (!(apparent_elevation_deg > 0.0)) return Rgb(0.0f);
  const double m = kasten_young_air_mass(90.0 - apparent_elevation_deg);
  const double beta = 0.04608 * turbidity - 0.04586;
  constexpr double kLambda[3] = {0.680, 0.550, 0.440};           // micrometres
  constexpr double kOzone[3] = {0.036, 0.085, 0.003};            // k_o (1/cm) at those wavelengths
  static const Rgb exo = xyY_to_linear_srgb(0.317, 0.326, 1.0);  // luminance 1
  constexpr double kExoKlx = 126.956;  // Preetham's table 2 over the sun's solid angle
  Rgb e;
  for (int c = 0; c < 3; ++c) {
    const double tau = 0.008735 * std::pow(kLambda[c], -4.08) + beta * std::pow(kLambda[c], -1.3) +
                       0.35 * kOzone[c];
    e[c] = static_cast<float>(kExoKlx * exo[c] * std::exp(-m * tau));
  }
  return e;
}

double usno_global_illuminance_lux(double h) {
  constexpr double kX = 753.66156;
  const double rh = h * std::numbers::pi / 180.0;
  const double s = std::asin(kX * std::cos(rh) / (kX + 1.0));
  const double mm = kX * (std::cos(s) - std::sin(rh)) + std::cos(s);
  const double m = std::exp(-0.21 * mm) * std::sin(rh) +
                   0.0289 * std::exp(-0.042 * mm) * (1.0 + (h + 90.0) * std::sin(rh) / 57.29577951);
  return 133775.0 * m;
}

double twilight_factor(double elevation_deg) {
  if (elevation_deg >= 0.0) return 1.0;
  constexpr double kNightLux = 0.002;  // airglow and starlight, moonless clear night
  const double at = usno_global_illuminance_lux(std::max(elevation_deg, -18.0));
  return std::max(at, kNightLux) / usno_global_illuminance_lux(0.0);
}

}  // namespace ambisim
