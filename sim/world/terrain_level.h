#pragma once
// A terrain imported the way game engines export it (the "level" object of a scenario's world
// section, documented in scenarios/README.md): a 16-bit heightmap (greyscale PNG, or RAW
// little-endian as Unity exports it), optionally an 8-bit sRGB albedo map, a canopy-height map
// and a water mask, all of the heightmap's pixel size. Files are read when the scenario is
// parsed and decoded into the cell arrays World builds from, so a World never touches the
// disk and a changed file changes the content hash.
//
// Orientation: image row 0 is the NORTH edge and column 0 the WEST edge (as a top-down map is
// drawn); pixel (i, j) of a W x H image is grid cell (ix = i, iy = H - 1 - j). RAW rows are
// read in the same order (first row north).
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "sim/colour/rgb.h"

namespace ambisim {

class ObjectReader;

struct TerrainLevel {
  int nx = 0, ny = 0;   // cells east x north (= the heightmap's width x height)
  double cell_m = 0.0;  // cell edge
  // Per cell, index iy * nx + ix, iy = 0 at the south edge.
  std::vector<float> ground_m;      // ground (or water surface) height
  std::vector<float> canopy_m;      // canopy height above the ground; empty without a map
  std::vector<std::uint8_t> water;  // 1 = water surface; empty without a mask
  std::vector<Rgb> albedo;          // linear RGB; empty: the biomes' albedos
  std::uint64_t content_hash = 0;   // of every decoded array and the grid
};

// Returns the bytes of the file at `path` (already resolved against the scenario's
// directory) or throws the reader's InputError at `key`. The default reads the disk; tests
// and the fuzzer pass bytes in memory.
using LevelFileReader =
    std::function<std::string(ObjectReader& r, const std::string& key, const std::string& path)>;
std::string read_level_file_from_disk(ObjectReader& r, const std::string& key,
                                      const std::string& path);

// Reads a "level" object: keys, then the files it names (paths relative to the directory of
// r.file(), or absolute), decoded and checked. Every error is an InputError naming the
// scenario file, the JSON path of the key and the image file.
TerrainLevel parse_terrain_level(ObjectReader& r,
                                 const LevelFileReader& read = read_level_file_from_disk);

}  // namespace ambisim
