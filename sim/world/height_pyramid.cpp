#include "sim/world/height_pyramid.h"

#include <algorithm>

namespace ambisim {

HeightPyramid::HeightPyramid(const std::vector<float>& h, int nx, int ny) {
  side_ = 1;
  while (side_ < nx || side_ < ny) side_ *= 2;
  std::size_t total = 0;
  for (int s = side_; s >= 1; s /= 2) {
    offset_.push_back(total);
    total += static_cast<std::size_t>(s) * static_cast<std::size_t>(s);
  }
  data_.assign(total, kEmpty);
  float* base = data_.data();
  for (int j = 0; j < ny; ++j) {
    std::copy_n(h.begin() + static_cast<std::ptrdiff_t>(j) * nx, nx,
                base + static_cast<std::ptrdiff_t>(j) * side_);
  }
  for (int level = 1; level < levels(); ++level) {
    const float* prev = level_data(level - 1);
    float* next = data_.data() + offset_[static_cast<std::size_t>(level)];
    const int s = size(level);
    const std::size_t ps = static_cast<std::size_t>(s) * 2;
    for (std::size_t j = 0; j < static_cast<std::size_t>(s); ++j) {
      for (std::size_t i = 0; i < static_cast<std::size_t>(s); ++i) {
        const std::size_t a = 2 * j * ps + 2 * i;
        next[j * static_cast<std::size_t>(s) + i] =
            std::max(std::max(prev[a], prev[a + 1]), std::max(prev[a + ps], prev[a + ps + 1]));
      }
    }
  }
}

}  // namespace ambisim
