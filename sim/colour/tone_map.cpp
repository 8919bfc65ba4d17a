#include "sim/colour/tone_map.h"

#include <algorithm>
#include <cmath>

namespace ambisim {
namespace {

glm::dvec3 non_negative(Rgb c) {
  return {std::max(0.0, double(c.x)), std::max(0.0, double(c.y)), std::max(0.0, double(c.z))};
}

// The tone map in double: display_lab feeds CIEDE2000 and should not carry float rounding.
glm::dvec3 reinhard(Rgb linear, double exposure) {
  const glm::dvec3 c = non_negative(linear) * exposure;
  const double y = srgb_luminance(c);
  // Black, and also a NaN exposure, map to black rather than dividing by 0.
  if (!(y > 0.0)) return glm::dvec3(0.0);
  glm::dvec3 out = c * (1.0 / (1.0 + y));  // == c * (y / (1 + y)) / y
  const double peak = std::max({out.x, out.y, out.z});
  if (peak > 1.0) out /= peak;
  // Keep [0, 1] exact against rounding in the division above.
  return {std::min(out.x, 1.0), std::min(out.y, 1.0), std::min(out.z, 1.0)};
}

}  // namespace

double log_average_luminance(std::span<const Rgb> linear, double delta) {
  if (linear.empty()) return 0.0;
  double sum_log = 0.0;
  for (const Rgb& c : linear) sum_log += std::log(delta + srgb_luminance(non_negative(c)));
  return std::exp(sum_log / static_cast<double>(linear.size()));
}

double exposure_for_key(double log_avg, double key) { return key / log_avg; }

Rgb tone_map_reinhard(Rgb linear, double exposure) { return Rgb(reinhard(linear, exposure)); }

Lab display_lab(Rgb linear, double exposure) {
  // reinhard() already returns [0, 1]^3, which is the clamp the display would apply.
  return linear_srgb_to_lab(reinhard(linear, exposure));
}

std::array<std::uint8_t, 3> to_srgb8(Rgb linear, double exposure) {
  const glm::dvec3 d = reinhard(linear, exposure);
  return {quantise_8bit(srgb_encode(d.x)), quantise_8bit(srgb_encode(d.y)),
          quantise_8bit(srgb_encode(d.z))};
}

}  // namespace ambisim
