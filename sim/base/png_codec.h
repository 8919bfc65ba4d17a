#pragma once
// PNG bytes <-> raw samples with libpng, for inputs a game engine exports (heightmaps, albedo
// and mask images) and the levels ambisim exports. Samples are returned exactly as stored: no
// gamma, no colour conversion (gAMA/sRGB/iCCP chunks are ignored; the caller knows what the
// image means). Palette images are expanded to RGB and greyscale below 8 bits to 8 bits, so
// a caller sees 1 (grey), 2 (grey + alpha), 3 (RGB) or 4 (RGBA) channels of 8 or 16 bits.
// Decoding never throws for bad bytes: it returns the reason, and the caller names the file
// and the JSON path in its InputError.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace ambisim {

struct PngSamples {
  int width = 0;
  int height = 0;
  int channels = 0;   // 1 grey, 2 grey + alpha, 3 RGB, 4 RGBA
  int bit_depth = 0;  // of the stored samples: 8 or 16 (palette and < 8-bit grey report 8)
  bool palette = false;
  // channels values per pixel, row-major, row 0 = the image's top row.
  std::vector<std::uint16_t> samples;

  std::uint16_t at(int x, int y, int c = 0) const {
    return samples[(static_cast<std::size_t>(y) * width + x) * channels + c];
  }
  std::uint16_t max_value() const { return bit_depth == 16 ? 65535 : 255; }
  // A w x h image of `channels` channels at `depth` bits, every sample 0.
  static PngSamples blank(int w, int h, int channels, int depth) {
    PngSamples img;
    img.width = w;
    img.height = h;
    img.channels = channels;
    img.bit_depth = depth;
    img.samples.assign(static_cast<std::size_t>(w) * h * channels, 0);
    return img;
  }
};

// At most this many pixels per side are decoded (the world grid's own limit).
inline constexpr int kPngMaxSide = 16384;

struct PngDecodeResult {
  std::optional<PngSamples> image;
  std::string error;  // one line, set iff !image
};

// Decodes a whole PNG file's bytes. Errors: not a PNG (bad signature), truncated or corrupt
// data (libpng's message), larger than kPngMaxSide.
PngDecodeResult decode_png(std::string_view bytes);

// Encodes samples (channels 1 or 3, bit depth 8 or 16, values <= max_value()) as a PNG with
// no ancillary chunks (no time stamp), so equal samples give byte-identical files. Throws
// std::invalid_argument for a malformed PngSamples.
std::string encode_png(const PngSamples& image);

}  // namespace ambisim
