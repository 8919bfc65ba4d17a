#include "sim/world/world_map.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace ambisim {
namespace {

std::uint8_t srgb8(double linear) {
  const double c = std::clamp(linear, 0.0, 1.0);
  const double s = c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
  return static_cast<std::uint8_t>(std::lround(s * 255.0));
}

}  // namespace

ImageRgb8 world_map_image(const World& w, int max_size_px) {
  const glm::dvec2 lo = w.min_xy(), hi = w.max_xy(), ext = hi - lo;
  const double px_m = std::max(ext.x, ext.y) / std::max(1, max_size_px);
  const int wpx = std::max(1, static_cast<int>(std::lround(ext.x / px_m)));
  const int hpx = std::max(1, static_cast<int>(std::lround(ext.y / px_m)));
  ImageRgb8 img(wpx, hpx);
  // A fixed light from the north-west for relief, independent of the scene's sun, so the map
  // reads the same at any time of day; the scene's shadows darken on top of it.
  const glm::dvec3 relief = glm::normalize(glm::dvec3(-1.0, 1.0, 1.5));
  for (int py = 0; py < hpx; ++py) {
    for (int px = 0; px < wpx; ++px) {
      const double x = lo.x + (px + 0.5) * px_m, y = hi.y - (py + 0.5) * px_m;
      const glm::dvec2 l = w.to_local(x, y);
      const int ix = std::clamp(static_cast<int>(l.x / w.cell_m()), 0, w.nx() - 1);
      const int iy = std::clamp(static_cast<int>(l.y / w.cell_m()), 0, w.ny() - 1);
      const glm::dvec3 n = w.cell_normal(ix, iy);
      double shade = 0.35 + 0.75 * std::max(0.0, glm::dot(n, relief)) / relief.z;
      const glm::dvec3 top(x, y, w.column_top(ix, iy));
      if (w.lighting().sun_on() && !w.sunlit(top)) shade *= 0.55;
      const Rgb a = w.cell_albedo(ix, iy);
      std::uint8_t* p = img.pixel(px, py);
      // Albedo 0.5 maps to about mid-grey: exposure 1.6 keeps snow just below white.
      for (int c = 0; c < 3; ++c) p[c] = srgb8(1.1 * a[c] * shade);
    }
  }
  // Road centre line as a thin white dashed stripe (every other 12 m).
  const Spline3& road = w.road();
  if (!road.empty()) {
    for (double s = 0.0; s < road.length(); s += 0.5 * px_m) {
      if (std::fmod(s, 24.0) > 12.0) continue;
      const glm::dvec3 q = road.at(s);
      const int px = static_cast<int>((q.x - lo.x) / px_m),
                py = static_cast<int>((hi.y - q.y) / px_m);
      if (px < 0 || py < 0 || px >= wpx || py >= hpx) continue;
      std::uint8_t* p = img.pixel(px, py);
      p[0] = p[1] = p[2] = 235;
    }
  }
  return img;
}

}  // namespace ambisim
