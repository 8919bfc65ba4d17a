#pragma once
// Maximum mip pyramid over a height grid (Tevs et al. 2008, "maximum mipmaps"): node (l, i, j)
// holds the highest column among the 2^l x 2^l cells it covers, so a ray segment that stays
// above a node's maximum can skip all of those cells at once.
#include <cstddef>
#include <vector>

namespace ambisim {

class HeightPyramid {
 public:
  // Padding cells beyond the grid (to a power-of-two square) are empty space.
  static constexpr float kEmpty = -1.0e30f;

  HeightPyramid() = default;
  // `h` is nx x ny, row-major (index iy * nx + ix); nx, ny >= 1.
  HeightPyramid(const std::vector<float>& h, int nx, int ny);

  int levels() const { return static_cast<int>(offset_.size()); }
  int size(int level) const { return side_ >> level; }  // nodes per side at `level`
  // Level 0 is the cells themselves; (ix, iy) must be within [0, size(level)).
  float max_at(int level, int ix, int iy) const {
    return level_data(level)[static_cast<std::size_t>(iy) * static_cast<std::size_t>(size(level)) +
                             static_cast<std::size_t>(ix)];
  }
  // Raw row-major data of one level (size(level)^2 values), for tight traversal loops. All
  // levels live in one flat array, level 0 first.
  const float* level_data(int level) const {
    return data_.data() + offset_[static_cast<std::size_t>(level)];
  }

 private:
  int side_ = 0;
  std::vector<float> data_;
  std::vector<std::size_t> offset_;  // start of each level in data_
};

}  // namespace ambisim
