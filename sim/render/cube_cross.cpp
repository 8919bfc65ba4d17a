#include "sim/render/cube_cross.h"

#include <array>

#include "sim/colour/tone_map.h"

namespace ambisim {
namespace {

constexpr int kCrossCols = 4;
constexpr int kCrossRows = 3;

// Face of each cell, row-major from the top; -1 = empty.
constexpr std::array<std::array<int, kCrossCols>, kCrossRows> kCrossLayout = {{
    {-1, static_cast<int>(CubeFace::PosZ), -1, -1},
    {static_cast<int>(CubeFace::NegX), static_cast<int>(CubeFace::PosY),
     static_cast<int>(CubeFace::PosX), static_cast<int>(CubeFace::NegY)},
    {-1, static_cast<int>(CubeFace::NegZ), -1, -1},
}};

}  // namespace

std::optional<CubeTexelRef> cube_cross_texel(int size, int x, int y) {
  if (size < 1 || x < 0 || y < 0 || x >= kCrossCols * size || y >= kCrossRows * size) {
    return std::nullopt;
  }
  const int cell = kCrossLayout[y / size][x / size];
  if (cell < 0) return std::nullopt;
  const auto face = static_cast<CubeFace>(cell);
  const int lx = x % size;  // left to right within the cell
  const int ly = y % size;  // top to bottom within the cell
  if (face == CubeFace::PosZ || face == CubeFace::NegZ) {
    // +Z (u, v, 1): u grows east, v north; north must be at the bottom (next to +Y), so the
    // stored row order (v growing downward on screen) is right. -Z (u, -v, -1): v grows south,
    // and south is at the bottom, away from +Y. Both: as stored.
    return CubeTexelRef{face, lx, ly};
  }
  // Side faces: u runs to the viewer's left when looking out from the centre (e.g. +Y is
  // (-u, 1, v)) and v runs up, so mirror columns and flip rows.
  return CubeTexelRef{face, size - 1 - lx, size - 1 - ly};
}

ImageRgb8 cube_cross_image(const CubeMap& cube, double exposure, int scale) {
  const int n = cube.size;
  ImageRgb8 img(kCrossCols * n * scale, kCrossRows * n * scale);
  for (int ty = 0; ty < kCrossRows * n; ++ty) {
    for (int tx = 0; tx < kCrossCols * n; ++tx) {
      const auto ref = cube_cross_texel(n, tx, ty);
      if (!ref) continue;  // already black
      const auto rgb = to_srgb8(cube.at(ref->face, ref->i, ref->j), exposure);
      for (int y = ty * scale; y < (ty + 1) * scale; ++y) {
        for (int x = tx * scale; x < (tx + 1) * scale; ++x) {
          std::uint8_t* p = img.pixel(x, y);
          p[0] = rgb[0];
          p[1] = rgb[1];
          p[2] = rgb[2];
        }
      }
    }
  }
  return img;
}

}  // namespace ambisim
