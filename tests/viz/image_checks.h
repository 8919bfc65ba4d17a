#pragma once
// Checks on written pictures shared by the viz tests.
#include <cstddef>
#include <cstdint>
#include <set>

#include "sim/base/image.h"

namespace ambisim::test {

// How many different RGB colours the image holds: a blank or single-colour render has 1.
inline std::size_t distinct_colours(const ImageRgb8& img) {
  std::set<std::uint32_t> c;
  for (std::size_t i = 0; i + 2 < img.rgb.size(); i += 3) {
    c.insert((std::uint32_t(img.rgb[i]) << 16) | (std::uint32_t(img.rgb[i + 1]) << 8) |
             img.rgb[i + 2]);
  }
  return c.size();
}

}  // namespace ambisim::test
