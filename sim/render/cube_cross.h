#pragma once
// The horizontal-cross picture of an HDR cube map, for looking at captures by eye.
//
// Layout (4 x 3 face cells, image row 0 at the top, sky up):
//            | +Z      |         |
//   -X west  | +Y north| +X east | -Y south
//            | -Z      |         |
// The middle row is the panorama seen turning right from inside (west, north, east, south);
// +Z and -Z attach above and below +Y. Each face is oriented so that pixels adjacent across an
// attached seam show adjacent directions (with the texel table of sim/sh/cube_map.h every side face
// is mirrored horizontally and flipped vertically, the Z faces are drawn as stored).
#include <optional>

#include "sim/base/image.h"
#include "sim/sh/cube_map.h"

namespace ambisim {

// The cube texel drawn at pixel (x, y) of a cross with one pixel per texel (scale 1):
// x in [0, 4 size), y in [0, 3 size). std::nullopt for the empty (black) cells.
struct CubeTexelRef {
  CubeFace face;
  int i;
  int j;
};
std::optional<CubeTexelRef> cube_cross_texel(int size, int x, int y);

// Tone-mapped cross (see tone_map.h, to_srgb8) of width 4 size scale, height 3 size scale; each
// texel becomes a scale x scale block, empty cells are black. size >= 1, scale >= 1.
ImageRgb8 cube_cross_image(const CubeMap& cube, double exposure, int scale = 8);

}  // namespace ambisim
