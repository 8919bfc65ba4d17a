#include "sim/world/terrain_noise.h"

#include <cmath>

#include "sim/base/hash.h"

namespace ambisim {
namespace {

double fade(double t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); }

double blend(double v00, double v10, double v01, double v11, double tx, double ty) {
  const double a = v00 + (v10 - v00) * tx, b = v01 + (v11 - v01) * tx;
  return a + (b - a) * ty;
}

// One octave along a row: calls emit(i, value) for the noise at (xs[i] * f + ox, y').
template <class Emit>
void octave_row(std::uint64_t seed, const double* xs, int n, double f, double ox, double yy,
                Emit emit) {
  const double fy = std::floor(yy);
  const auto iy = static_cast<std::int64_t>(fy);
  const double ty = fade(yy - fy);
  std::int64_t last = 0;
  bool have = false;
  double v00 = 0, v10 = 0, v01 = 0, v11 = 0;
  for (int i = 0; i < n; ++i) {
    const double x = xs[i] * f + ox;
    const double fx = std::floor(x);
    const auto ix = static_cast<std::int64_t>(fx);
    if (!have || ix != last) {
      if (have && ix == last + 1) {
        v00 = v10;
        v01 = v11;
      } else {
        v00 = hash_unit(seed, ix, iy);
        v01 = hash_unit(seed, ix, iy + 1);
      }
      v10 = hash_unit(seed, ix + 1, iy);
      v11 = hash_unit(seed, ix + 1, iy + 1);
      last = ix;
      have = true;
    }
    emit(i, blend(v00, v10, v01, v11, fade(x - fx), ty));
  }
}

}  // namespace

double value_noise(std::uint64_t seed, double x, double y) {
  const double fx = std::floor(x), fy = std::floor(y);
  const auto ix = static_cast<std::int64_t>(fx), iy = static_cast<std::int64_t>(fy);
  return blend(hash_unit(seed, ix, iy), hash_unit(seed, ix + 1, iy), hash_unit(seed, ix, iy + 1),
               hash_unit(seed, ix + 1, iy + 1), fade(x - fx), fade(y - fy));
}

void value_noise_row(std::uint64_t seed, const double* xs, int n, double y, double* out) {
  octave_row(seed, xs, n, 1.0, 0.0, y, [&](int i, double v) { out[i] = v; });
}

void fbm_noise_row(std::uint64_t seed, const double* xs, int n, double y, double wavelength_m,
                   int octaves, double persistence, double* out) {
  double norm = 0.0, amp = 1.0, f = 1.0 / wavelength_m;
  for (int i = 0; i < n; ++i) out[i] = 0.0;
  for (int o = 0; o < octaves; ++o) {
    const std::uint64_t s = hash_combine(seed, static_cast<std::uint64_t>(o));
    const double a = amp;
    octave_row(s, xs, n, f, 17.31 * o, y * f - 9.77 * o, [&](int i, double v) { out[i] += a * v; });
    norm += amp;
    amp *= persistence;
    f *= 2.0;
  }
  for (int i = 0; i < n; ++i) out[i] /= norm;
}

void ridged_noise_row(std::uint64_t seed, const double* xs, int n, double y, double wavelength_m,
                      int octaves, double persistence, double* out) {
  double norm = 0.0, amp = 1.0, f = 1.0 / wavelength_m;
  for (int i = 0; i < n; ++i) out[i] = 0.0;
  for (int o = 0; o < octaves; ++o) {
    const std::uint64_t s = hash_combine(seed ^ 0x5bd1e995ull, static_cast<std::uint64_t>(o));
    const double a = amp;
    octave_row(s, xs, n, f, 3.1 * o, y * f + 7.3 * o, [&](int i, double v) {
      const double r = 1.0 - std::abs(2.0 * v - 1.0);
      out[i] += a * r * r;
    });
    norm += amp;
    amp *= persistence;
    f *= 2.0;
  }
  for (int i = 0; i < n; ++i) out[i] /= norm;
}

double fbm_noise(std::uint64_t seed, double x, double y, double wavelength_m, int octaves,
                 double persistence) {
  double sum = 0.0, norm = 0.0, amp = 1.0, f = 1.0 / wavelength_m;
  for (int o = 0; o < octaves; ++o) {
    // Per-octave seed and offset so octaves do not share lattice points at the origin.
    const std::uint64_t s = hash_combine(seed, static_cast<std::uint64_t>(o));
    sum += amp * value_noise(s, x * f + 17.31 * o, y * f - 9.77 * o);
    norm += amp;
    amp *= persistence;
    f *= 2.0;
  }
  return sum / norm;
}

double ridged_noise(std::uint64_t seed, double x, double y, double wavelength_m, int octaves,
                    double persistence) {
  double sum = 0.0, norm = 0.0, amp = 1.0, f = 1.0 / wavelength_m;
  for (int o = 0; o < octaves; ++o) {
    const std::uint64_t s = hash_combine(seed ^ 0x5bd1e995ull, static_cast<std::uint64_t>(o));
    const double r = 1.0 - std::abs(2.0 * value_noise(s, x * f + 3.1 * o, y * f + 7.3 * o) - 1.0);
    sum += amp * r * r;
    norm += amp;
    amp *= persistence;
    f *= 2.0;
  }
  return sum / norm;
}

}  // namespace ambisim
