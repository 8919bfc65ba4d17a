#include "sim/world/height_fog.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ambisim {

double FogState::sigma_at(double z) const {
  double s = homogeneous_per_m;
  if (height) s += density_per_m * std::exp(-(z - base_m) / falloff_m);
  return s;
}

double FogState::optical_depth(const glm::dvec3& o, const glm::dvec3& d, double t) const {
  double tau = 0.0;
  const bool escaping = !std::isfinite(t);
  if (!escaping) tau += homogeneous_per_m * t;
  if (height && density_per_m > 0.0) {
    const double k = density_per_m * std::exp(-(o.z - base_m) / falloff_m);
    const double a = d.z / falloff_m;  // decay rate along the ray (1/m)
    if (escaping) {
      tau += a > 1e-9 ? k / a : std::numeric_limits<double>::infinity();
    } else if (std::abs(a * t) < 1e-6) {
      tau += k * t * (1.0 - 0.5 * a * t);  // series: (1 - e^{-a t}) / a
    } else {
      tau += k * (1.0 - std::exp(-a * t)) / a;
    }
  }
  return tau;
}

FogState fog_at(const FogParams& p, double t) {
  FogState f;
  f.homogeneous_per_m = p.extinction_per_m;
  f.height = p.height_enabled && !p.height_keys.empty();
  f.falloff_m = p.falloff_m;
  if (!f.height) return f;
  const auto& k = p.height_keys;
  if (t <= k.front().time_s || k.size() == 1) {
    f.density_per_m = k.front().density_per_m;
    f.base_m = k.front().base_m;
  } else if (t >= k.back().time_s) {
    f.density_per_m = k.back().density_per_m;
    f.base_m = k.back().base_m;
  } else {
    const auto it =
        std::upper_bound(k.begin(), k.end(), t,
                         [](double x, const FogParams::HeightKey& h) { return x < h.time_s; });
    const auto& b = *it;
    const auto& a = *(it - 1);
    const double u = (t - a.time_s) / (b.time_s - a.time_s);
    f.density_per_m = a.density_per_m + u * (b.density_per_m - a.density_per_m);
    f.base_m = a.base_m + u * (b.base_m - a.base_m);
  }
  return f;
}

}  // namespace ambisim
