#include "policies/baselines/ddgi_blend.h"

#include <algorithm>
#include <cmath>

namespace ambisim {

float ddgi_luminance(const Sh9Rgb& sh) {
  const Rgb& c = sh.c[0];
  return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z;
}

double ddgi_effective_hysteresis(const Sh9Rgb& value, const Sh9Rgb& target,
                                 const DdgiBlendSettings& s) {
  double h = std::clamp(s.hysteresis, 0.0, 1.0);
  if (s.irradiance_threshold <= 0.0) return h;
  const Rgb& v = value.c[0];
  const Rgb& t = target.c[0];
  const double diff =
      std::max({std::abs(static_cast<double>(t.x) - v.x), std::abs(static_cast<double>(t.y) - v.y),
                std::abs(static_cast<double>(t.z) - v.z)});
  const double scale =
      std::max({std::abs(static_cast<double>(v.x)), std::abs(static_cast<double>(v.y)),
                std::abs(static_cast<double>(v.z)), 1e-6});
  if (diff > s.irradiance_threshold * scale) {
    h = std::max(0.0, h - DdgiBlendSettings::kBigChangeReduction);
  }
  return h;
}

double ddgi_blend_fraction(const Sh9Rgb& value, const Sh9Rgb& target, double dt,
                           const DdgiBlendSettings& s) {
  if (!(dt > 0.0)) return 0.0;
  const double frames = dt * s.reference_rate_hz;
  const double h = ddgi_effective_hysteresis(value, target, s);
  double f = 1.0 - std::pow(h, frames);  // h = 0: 1 (pow(0, x > 0) = 0)
  const double lum = ddgi_luminance(value);
  const double rise = f * (static_cast<double>(ddgi_luminance(target)) - lum);
  if (s.brightness_threshold > 0.0 && lum > 0.0 && rise > 0.0) {
    const double limit = (std::pow(1.0 + s.brightness_threshold, frames) - 1.0) * lum;
    if (rise > limit) f *= limit / rise;
  }
  return std::clamp(f, 0.0, 1.0);
}

}  // namespace ambisim
