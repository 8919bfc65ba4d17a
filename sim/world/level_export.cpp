#include "sim/world/level_export.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "sim/colour/cielab.h"
#include "sim/world/world.h"

namespace ambisim {
namespace {

int lattice_index(double local_m, double cell_m, const char* what) {
  const double n = local_m / cell_m;
  if (std::abs(n - std::round(n)) > 1e-6) {
    throw std::invalid_argument(std::string("the region's ") + what +
                                " is not on the world's cell lattice");
  }
  return static_cast<int>(std::lround(n));
}

std::uint16_t quantise(double v, double max_code) {
  return static_cast<std::uint16_t>(std::clamp(std::round(v * max_code), 0.0, max_code));
}

}  // namespace

nlohmann::json ExportedLevel::level_object(const std::string& dir) const {
  const std::string d = dir.empty() || dir.back() == '/' ? dir : dir + "/";
  return {{"heightmap", d + "height.png"},    {"cell_m", cell_m},
          {"height_scale_m", height_scale_m}, {"height_offset_m", height_offset_m},
          {"albedo", d + "albedo.png"},       {"canopy", d + "canopy.png"},
          {"canopy_scale_m", canopy_scale_m}, {"water", d + "water.png"}};
}

ExportedLevel export_level(const World& world, glm::dvec2 min, glm::dvec2 max, int stride) {
  if (stride < 1) throw std::invalid_argument("the stride must be >= 1");
  const glm::dvec2 lo = world.to_local(min.x, min.y), hi = world.to_local(max.x, max.y);
  const int i0 = lattice_index(lo.x, world.cell_m(), "west edge");
  const int j0 = lattice_index(lo.y, world.cell_m(), "south edge");
  const int i1 = lattice_index(hi.x, world.cell_m(), "east edge");
  const int j1 = lattice_index(hi.y, world.cell_m(), "north edge");
  if (i0 < 0 || j0 < 0 || i1 > world.nx() || j1 > world.ny() || i1 <= i0 || j1 <= j0) {
    throw std::invalid_argument("the region must be a non-empty part of the world's grid");
  }
  if ((i1 - i0) % stride != 0 || (j1 - j0) % stride != 0) {
    throw std::invalid_argument("the region's size must be a multiple of the stride in cells");
  }
  const int w = (i1 - i0) / stride, h = (j1 - j0) / stride;
  if (w < 2 || h < 2) throw std::invalid_argument("the region must be at least 2 x 2 cells");
  ExportedLevel out;
  out.cell_m = world.cell_m() * stride;
  out.origin = min;
  // Sample every new cell first, then quantise against the extremes.
  const std::size_t n = static_cast<std::size_t>(w) * h;
  std::vector<double> ground(n), canopy(n);
  std::vector<Rgb> albedo(n);
  std::vector<bool> water(n);
  double g_min = 1e300, g_max = -1e300, c_max = 0.0;
  for (int j = 0; j < h; ++j) {  // image row, north first
    const int cy = h - 1 - j;    // new cell row, south first
    for (int i = 0; i < w; ++i) {
      const double x = min.x + (i + 0.5) * out.cell_m, y = min.y + (cy + 0.5) * out.cell_m;
      const glm::dvec2 l = world.to_local(x, y);
      const int ix = std::min(static_cast<int>(l.x / world.cell_m()), world.nx() - 1);
      const int iy = std::min(static_cast<int>(l.y / world.cell_m()), world.ny() - 1);
      const std::size_t k = static_cast<std::size_t>(j) * w + i;
      ground[k] = world.ground_height(x, y);
      const Biome b = world.cell_biome(ix, iy);
      canopy[k] = b == Biome::Forest ? world.column_top(ix, iy) - world.column_ground(ix, iy) : 0;
      water[k] = b == Biome::Water;
      albedo[k] = world.cell_albedo(ix, iy);
      g_min = std::min(g_min, ground[k]);
      g_max = std::max(g_max, ground[k]);
      c_max = std::max(c_max, canopy[k]);
    }
  }
  // Whole metres for the offset and the scale: readable numbers in the level object.
  out.height_offset_m = std::floor(g_min);
  out.height_scale_m = std::max(1.0, std::ceil(g_max) - out.height_offset_m);
  out.canopy_scale_m = std::max(1.0, std::ceil(c_max));
  out.heightmap = PngSamples::blank(w, h, 1, 16);
  out.albedo = PngSamples::blank(w, h, 3, 8);
  out.canopy = PngSamples::blank(w, h, 1, 8);
  out.water = PngSamples::blank(w, h, 1, 8);
  for (std::size_t k = 0; k < n; ++k) {
    out.heightmap.samples[k] =
        quantise((ground[k] - out.height_offset_m) / out.height_scale_m, 65535.0);
    for (int c = 0; c < 3; ++c) {
      out.albedo.samples[3 * k + c] = quantise(srgb_encode(albedo[k][c]), 255.0);
    }
    // A forest cell keeps at least one code: 0 would turn it into open ground.
    const std::uint16_t cc = quantise(canopy[k] / out.canopy_scale_m, 255.0);
    out.canopy.samples[k] = canopy[k] > 0.0 ? std::max<std::uint16_t>(cc, 1) : 0;
    out.water.samples[k] = water[k] ? 255 : 0;
  }
  return out;
}

}  // namespace ambisim
