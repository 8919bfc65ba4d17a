#include "sim/colour/ciede2000.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace ambisim {
namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;
constexpr double kPow25To7 = 6103515625.0;  // 25^7

// Hue angle in degrees in [0, 360); 0 for the achromatic case (Sharma eq. 4: a' = b' = 0).
double hue_deg(double b, double a_prime) {
  if (b == 0.0 && a_prime == 0.0) return 0.0;
  const double h = std::atan2(b, a_prime) / kDegToRad;
  return h < 0.0 ? h + 360.0 : h;
}

}  // namespace

double ciede2000(const Lab& lab1, const Lab& lab2, const Ciede2000Weights& w) {
  // Step 1: a' rescaled by G so that near-neutral colours get a larger a' (Sharma eqs. 2-5).
  const double c1 = std::hypot(lab1.a, lab1.b);
  const double c2 = std::hypot(lab2.a, lab2.b);
  const double c_bar = 0.5 * (c1 + c2);
  const double c_bar7 = std::pow(c_bar, 7.0);
  const double g = 0.5 * (1.0 - std::sqrt(c_bar7 / (c_bar7 + kPow25To7)));
  const double a1p = (1.0 + g) * lab1.a;
  const double a2p = (1.0 + g) * lab2.a;
  const double c1p = std::hypot(a1p, lab1.b);
  const double c2p = std::hypot(a2p, lab2.b);
  const double h1p = hue_deg(lab1.b, a1p);
  const double h2p = hue_deg(lab2.b, a2p);

  // Step 2: differences (eqs. 8-11). The hue difference takes the short way round the circle
  // and is 0 when either colour is achromatic (its hue is undefined).
  const double dLp = lab2.L - lab1.L;
  const double dCp = c2p - c1p;
  const bool achromatic = c1p * c2p == 0.0;
  double dhp = 0.0;
  if (!achromatic) {
    dhp = h2p - h1p;
    if (dhp > 180.0) {
      dhp -= 360.0;
    } else if (dhp < -180.0) {
      dhp += 360.0;
    }
  }
  const double dHp = 2.0 * std::sqrt(c1p * c2p) * std::sin(0.5 * dhp * kDegToRad);

  // Step 3: means and weighting functions (eqs. 12-22). The mean hue is the mid-point on the
  // short arc; with an achromatic colour it is the plain sum (Sharma eq. 14, last case).
  const double Lp_bar = 0.5 * (lab1.L + lab2.L);
  const double Cp_bar = 0.5 * (c1p + c2p);
  double hp_bar = h1p + h2p;
  if (!achromatic) {
    if (std::abs(h1p - h2p) <= 180.0) {
      hp_bar *= 0.5;
    } else if (hp_bar < 360.0) {
      hp_bar = 0.5 * (hp_bar + 360.0);
    } else {
      hp_bar = 0.5 * (hp_bar - 360.0);
    }
  }
  const double t = 1.0 - 0.17 * std::cos((hp_bar - 30.0) * kDegToRad) +
                   0.24 * std::cos(2.0 * hp_bar * kDegToRad) +
                   0.32 * std::cos((3.0 * hp_bar + 6.0) * kDegToRad) -
                   0.20 * std::cos((4.0 * hp_bar - 63.0) * kDegToRad);
  const double d_theta = 30.0 * std::exp(-std::pow((hp_bar - 275.0) / 25.0, 2.0));
  const double Cp_bar7 = std::pow(Cp_bar, 7.0);
  const double r_c = 2.0 * std::sqrt(Cp_bar7 / (Cp_bar7 + kPow25To7));
  const double l50 = (Lp_bar - 50.0) * (Lp_bar - 50.0);
  const double s_l = 1.0 + 0.015 * l50 / std::sqrt(20.0 + l50);
  const double s_c = 1.0 + 0.045 * Cp_bar;
  const double s_h = 1.0 + 0.015 * Cp_bar * t;
  const double r_t = -std::sin(2.0 * d_theta * kDegToRad) * r_c;

  const double tl = dLp / (w.k_l * s_l);
  const double tc = dCp / (w.k_c * s_c);
  const double th = dHp / (w.k_h * s_h);
  // The rotation term is bounded by tc^2 + th^2, so the sum is >= 0 up to rounding.
  return std::sqrt(std::max(0.0, tl * tl + tc * tc + th * th + r_t * tc * th));
}

}  // namespace ambisim
