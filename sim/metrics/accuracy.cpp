#include "sim/metrics/accuracy.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

#include "sim/colour/ciede2000.h"
#include "sim/colour/tone_map.h"

namespace ambisim {

double relative_error(const Rgb& p, const Rgb& r, double floor) {
  // Double before subtracting: float differences of close HDR values lose digits.
  const glm::dvec3 pd(p);
  const glm::dvec3 rd(r);
  return glm::length(pd - rd) / std::max(glm::length(rd), floor);
}

double display_difference(const Lab& p, const Lab& r) { return ciede2000(p, r); }

double display_difference(const Rgb& p, const Rgb& r, double exposure) {
  return ciede2000(display_lab(p, exposure), display_lab(r, exposure));
}

double reference_exposure(std::span<const Rgb> reference_irradiance, double key) {
  const double log_avg = log_average_luminance(reference_irradiance);
  // log_average_luminance is 0 only for empty input; use its delta (1e-4) instead, which is
  // also what an all-black reference averages to.
  return exposure_for_key(log_avg > 0.0 ? log_avg : 1e-4, key);
}

std::vector<glm::dvec3> normal_set(std::string_view name) {
  if (name == "axes6") {
    return {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  }
  if (name == "axes26") {
    std::vector<glm::dvec3> out;
    for (int i = -1; i <= 1; ++i) {
      for (int j = -1; j <= 1; ++j) {
        for (int k = -1; k <= 1; ++k) {
          if (i == 0 && j == 0 && k == 0) continue;
          out.push_back(glm::normalize(glm::dvec3(i, j, k)));
        }
      }
    }
    return out;
  }
  throw std::invalid_argument("unknown normal set '" + std::string(name) +
                              "' (expected axes6 or axes26)");
}

}  // namespace ambisim
