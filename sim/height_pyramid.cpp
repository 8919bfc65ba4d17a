#include "sim/height_pyramid.h"

#include <algorithm>

namespace ambisim {

HeightPyramid::HeightPyramid(const std::vector<float>& h, int nx, int ny) {
  side_ = 1;
  while (side_ < nx || side_ < ny) side_ *= 2;
  std::vector<float> base(static_cast<std::size_t>(side_) * side_, kEmpty);
  for (int j = 0; j < ny; ++j) {
    std::copy_n(h.begin() + static_cast<std::ptrdiff_t>(j) * nx, nx,
                base.begin() + static_cast<std::ptrdiff_t>(j) * side_);
  }
  level_.push_back(std::move(base));
  for (int s = side_ / 2; s >= 1; s /= 2) {
    const std::vector<float>& prev = level_.back();
    std::vector<float> next(static_cast<std::size_t>(s) * s);
    const std::size_t ps = static_cast<std::size_t>(s) * 2;
    for (int j = 0; j < s; ++j) {
      for (int i = 0; i < s; ++i) {
        const std::size_t a = 2 * j * ps + 2 * i;
        next[static_cast<std::size_t>(j) * s + i] =
            std::max(std::max(prev[a], prev[a + 1]), std::max(prev[a + ps], prev[a + ps + 1]));
      }
    }
    level_.push_back(std::move(next));
  }
}

}  // namespace ambisim
