#pragma once
// A piece of a world written the way engines export a terrain, so that it imports back as a
// level (terrain_level.h): a 16-bit greyscale heightmap, an 8-bit sRGB albedo map, an 8-bit
// canopy-height map and an 8-bit water mask, row 0 north, plus the numbers the level object
// needs (height scale and offset, canopy scale, cell size). Made for examples and tests: the
// export quantises (heights to 1/65535 of their range, albedo to 8-bit sRGB, canopy to 1/255
// of its maximum) and drops what a level cannot carry (the road's spline, the biome classes
// other than water and forest).
#include <string>

#include <glm/vec2.hpp>
#include <nlohmann/json.hpp>

#include "sim/base/png_codec.h"

namespace ambisim {

class World;

struct ExportedLevel {
  PngSamples heightmap, albedo, canopy, water;
  double cell_m = 0.0;
  double height_scale_m = 0.0, height_offset_m = 0.0, canopy_scale_m = 0.0;
  glm::dvec2 origin{0.0};  // world-frame south-west corner of the piece

  // The world section's "level" object for files named height.png, albedo.png, canopy.png
  // and water.png in `dir` (relative to the scenario that uses it).
  nlohmann::json level_object(const std::string& dir) const;
};

// Exports the square-celled region [min, max) (world metres, on the world's cell lattice,
// inside the grid) sampled every `stride` cells: a new cell of stride x cell_m takes the
// ground height at its centre (bilinear) and the albedo, biome and canopy of the world cell
// there. Throws std::invalid_argument for a region off the lattice or outside the grid.
ExportedLevel export_level(const World& world, glm::dvec2 min, glm::dvec2 max, int stride);

}  // namespace ambisim
