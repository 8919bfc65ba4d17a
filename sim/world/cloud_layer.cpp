#include "sim/world/cloud_layer.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "sim/base/hash.h"

namespace ambisim {
namespace {

constexpr int kOctaves = 5;

double smoothstep(double a, double b, double x) {
  if (b <= a) return x < a ? 0.0 : 1.0;
  const double t = std::clamp((x - a) / (b - a), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

// Value noise with lattice period `period` (cells), so the tile repeats seamlessly.
double periodic_value_noise(std::uint64_t seed, double x, double y, int period) {
  const double fx = std::floor(x), fy = std::floor(y);
  const auto wrap = [period](double v) {
    const auto i = static_cast<std::int64_t>(v) % period;
    return i < 0 ? i + period : i;
  };
  const std::int64_t x0 = wrap(fx), y0 = wrap(fy), x1 = wrap(fx + 1), y1 = wrap(fy + 1);
  const double tx = x - fx, ty = y - fy;
  const double sx = tx * tx * tx * (tx * (tx * 6 - 15) + 10);
  const double sy = ty * ty * ty * (ty * (ty * 6 - 15) + 10);
  const double a = hash_unit(seed, x0, y0), b = hash_unit(seed, x1, y0);
  const double c = hash_unit(seed, x0, y1), d = hash_unit(seed, x1, y1);
  return (a + (b - a) * sx) + ((c + (d - c) * sx) - (a + (b - a) * sx)) * sy;
}

}  // namespace

CloudLayer::CloudLayer(const CloudParams& p, double layer_z) : p_(p), z_(layer_z) {
  // The wind blows toward wind_from + 180 degrees (compass: 0 north = +y, 90 east = +x).
  const double to = (p.wind_from_deg + 180.0) * std::numbers::pi / 180.0;
  wind_ = glm::dvec2(std::sin(to), std::cos(to)) * p.wind_mps;
  texel_m_ = 8.0 * p.scale_m / kTexels;
  // Octave o: lattice period 8 * 2^o cells over the tile (the first has 8 features per tile,
  // i.e. features of scale_m), amplitude 0.5^o.
  std::vector<float> f(static_cast<std::size_t>(kTexels) * kTexels);
  for (int j = 0; j < kTexels; ++j) {
    for (int i = 0; i < kTexels; ++i) {
      double sum = 0.0, amp = 1.0, norm = 0.0;
      for (int o = 0; o < kOctaves; ++o) {
        const int period = 8 << o;
        const double u = (i + 0.5) * period / kTexels, v = (j + 0.5) * period / kTexels;
        sum += amp * periodic_value_noise(hash_combine(p.seed, 0xC10D + o), u, v, period);
        norm += amp;
        amp *= 0.5;
      }
      f[static_cast<std::size_t>(j) * kTexels + i] = static_cast<float>(sum / norm);
    }
  }
  // Threshold at the (1 - coverage) quantile, so that `coverage` of the texels lie above it.
  std::vector<float> sorted = f;
  std::sort(sorted.begin(), sorted.end());
  const double lo_v = sorted.front(), hi_v = sorted.back();
  const double q =
      p.coverage >= 1.0
          ? lo_v - 1.0
          : (p.coverage <= 0.0
                 ? hi_v + 1.0
                 : sorted[static_cast<std::size_t>((1.0 - p.coverage) * (sorted.size() - 1))]);
  const double half = 0.5 * p.softness * (hi_v - lo_v);
  c_.resize(f.size());
  double sum = 0.0;
  for (std::size_t k = 0; k < f.size(); ++k) {
    c_[k] = static_cast<float>(smoothstep(q - half, q + half, f[k]));
    sum += c_[k];
  }
  mean_ = sum / static_cast<double>(c_.size());
}

double CloudLayer::sample(double u, double v) const {
  const double fu = std::floor(u), fv = std::floor(v);
  const auto wrap = [](double x) {
    const auto i = static_cast<std::int64_t>(x) % kTexels;
    return static_cast<std::size_t>(i < 0 ? i + kTexels : i);
  };
  const std::size_t i0 = wrap(fu), j0 = wrap(fv), i1 = wrap(fu + 1), j1 = wrap(fv + 1);
  const double a = u - fu, b = v - fv;
  const double c00 = c_[j0 * kTexels + i0], c10 = c_[j0 * kTexels + i1];
  const double c01 = c_[j1 * kTexels + i0], c11 = c_[j1 * kTexels + i1];
  return (c00 + (c10 - c00) * a) + ((c01 + (c11 - c01) * a) - (c00 + (c10 - c00) * a)) * b;
}

double CloudLayer::cover(double x, double y, double t) const {
  return sample((x - wind_.x * t) / texel_m_ - 0.5, (y - wind_.y * t) / texel_m_ - 0.5);
}

double CloudLayer::sun_transmittance(const glm::dvec3& p, const glm::dvec3& s, double t) const {
  if (s.z <= 1e-6 || p.z >= z_) return 1.0;
  const double k = (z_ - p.z) / s.z;
  return 1.0 - p_.opacity * cover(p.x + s.x * k, p.y + s.y * k, t);
}

double CloudLayer::cover_along(const glm::dvec3& o, const glm::dvec3& d, double t) const {
  if (d.z <= 1e-6 || o.z >= z_) return 0.0;
  const double k = (z_ - o.z) / d.z;
  // Far toward the horizon the layer is seen through haze: fade it out below 3 degrees.
  const double fade = smoothstep(0.0, 0.05, d.z);
  return fade * cover(o.x + d.x * k, o.y + d.y * k, t);
}

double CloudLayer::change_rate(const glm::dvec3& p, const glm::dvec3& s, double t) const {
  if (s.z <= 1e-6 || p.z >= z_) return 0.0;
  const double k = (z_ - p.z) / s.z;
  const double x = p.x + s.x * k, y = p.y + s.y * k, h = texel_m_;
  const double gx = (cover(x + h, y, t) - cover(x - h, y, t)) / (2.0 * h);
  const double gy = (cover(x, y + h, t) - cover(x, y - h, t)) / (2.0 * h);
  return p_.opacity * std::abs(gx * wind_.x + gy * wind_.y);
}

}  // namespace ambisim
