#include "sim/world/shadow_heights.h"

#include <algorithm>
#include <cmath>

namespace ambisim {

// Shadow-height sweep: S(c) = max(H(q), S(q)) - |q - c| tan(elevation), where q is one cell
// toward the sun along the dominant axis (linear interpolation across the other axis), so
// cells are processed in rows moving away from the sun in O(cells).
std::vector<float> shadow_heights(const std::vector<float>& surface, int nx, int ny, double cell_m,
                                  const glm::dvec3& s, bool sun_on) {
  std::vector<float> shadow(surface.size(), kNoShadow);
  const double horiz = std::hypot(s.x, s.y);
  if (!sun_on) {
    std::fill(shadow.begin(), shadow.end(), std::numeric_limits<float>::infinity());
    return shadow;
  }
  if (horiz < 1e-9) return shadow;  // sun at the zenith: nothing is shadowed
  const double tan_e = s.z / horiz;
  const bool x_major = std::abs(s.x) >= std::abs(s.y);
  const int n_major = x_major ? nx : ny, n_minor = x_major ? ny : nx;
  const double a_major = x_major ? s.x : s.y, a_minor = x_major ? s.y : s.x;
  const int step = a_major > 0 ? 1 : -1;
  const double slope = a_minor / std::abs(a_major);  // minor offset per major step (cells)
  const double drop = cell_m * std::sqrt(1.0 + slope * slope) * tan_e;
  auto at = [&](int major, int minor) -> std::size_t {
    return x_major ? static_cast<std::size_t>(minor) * nx + major
                   : static_cast<std::size_t>(major) * nx + minor;
  };
  const int first = step > 0 ? n_major - 2 : 1;
  for (int m = first; m >= 0 && m < n_major; m -= step) {
    const int up = m + step;
    for (int k = 0; k < n_minor; ++k) {
      const double q = k + slope;
      const int q0 = static_cast<int>(std::floor(q));
      const double f = q - q0;
      auto blocker = [&](int kk) -> double {
        if (kk < 0 || kk >= n_minor) return kNoShadow;
        const std::size_t idx = at(up, kk);
        return std::max<double>(surface[idx], shadow[idx]);
      };
      const double b0 = blocker(q0), b1 = blocker(q0 + 1);
      // Interpolate only between real blockers; next to the border take the one that exists.
      double b;
      if (b0 <= kNoShadow) {
        b = f > 0.0 ? b1 : kNoShadow;
      } else if (b1 <= kNoShadow) {
        b = f < 1.0 ? b0 : kNoShadow;
      } else {
        b = b0 + (b1 - b0) * f;
      }
      shadow[at(m, k)] = b <= kNoShadow ? kNoShadow : static_cast<float>(b - drop);
    }
  }
  return shadow;
}

}  // namespace ambisim
