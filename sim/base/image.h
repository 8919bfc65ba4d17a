#pragma once
// A plain 8-bit RGB raster, top row first. sim/ fills it; viz/ writes it to PNG.
#include <cstdint>
#include <vector>

namespace ambisim {

struct ImageRgb8 {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;  // 3 bytes per pixel, row-major, row 0 at the top

  ImageRgb8() = default;
  ImageRgb8(int w, int h) : width(w), height(h), rgb(static_cast<std::size_t>(w) * h * 3, 0) {}
  std::uint8_t* pixel(int x, int y) { return &rgb[(static_cast<std::size_t>(y) * width + x) * 3]; }
  const std::uint8_t* pixel(int x, int y) const {
    return &rgb[(static_cast<std::size_t>(y) * width + x) * 3];
  }
};

}  // namespace ambisim
