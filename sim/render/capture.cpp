#include "sim/render/capture.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <vector>

namespace ambisim {
namespace {

// Faces up to this size keep their texel directions in a table shared by every capture.
constexpr int kMaxTabulatedSize = 128;

// The unit texel directions of every face of an n x n cube map, [face][j][i] as CubeMap
// stores texels: computed once per size (the same cube_texel_direction values), shared
// read-only by every thread.
const std::vector<glm::dvec3>& texel_directions(int n) {
  static std::mutex mutex;
  static std::map<int, std::unique_ptr<const std::vector<glm::dvec3>>> tables;
  const std::lock_guard<std::mutex> lock(mutex);
  std::unique_ptr<const std::vector<glm::dvec3>>& table = tables[n];
  if (!table) {
    auto dirs = std::make_unique<std::vector<glm::dvec3>>();
    dirs->reserve(static_cast<std::size_t>(kCubeFaces) * static_cast<std::size_t>(n) *
                  static_cast<std::size_t>(n));
    for (int f = 0; f < kCubeFaces; ++f) {
      for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
          dirs->push_back(cube_texel_direction(static_cast<CubeFace>(f), n, i, j));
        }
      }
    }
    table = std::move(dirs);
  }
  return *table;
}

}  // namespace

glm::dvec3 capture_origin(const World& w, const glm::dvec3& p) {
  if (!w.contains_xy(p.x, p.y)) {
    return {p.x, p.y, std::max(p.z, w.far_ground_height() + kCaptureLift)};
  }
  const glm::dvec2 l = w.to_local(p.x, p.y);
  const int ix = std::min(static_cast<int>(l.x / w.cell_m()), w.nx() - 1);
  const int iy = std::min(static_cast<int>(l.y / w.cell_m()), w.ny() - 1);
  const double top = w.column_top(ix, iy);
  return {p.x, p.y, std::max(p.z, top + kCaptureLift)};
}

void capture_face(const Illumination& il, const glm::dvec3& p, CubeFace face, CubeMap& inout,
                  Marcher marcher) {
  const World& w = il.world();
  const glm::dvec3 o = capture_origin(w, p);
  const int n = inout.size;
  if (n <= kMaxTabulatedSize) {
    const std::vector<glm::dvec3>& dirs = texel_directions(n);
    const std::size_t first = inout.index(face, 0, 0), count = static_cast<std::size_t>(n) * n;
    for (std::size_t k = first; k < first + count; ++k) {
      inout.texel[k] = trace_radiance(il, o, dirs[k], marcher);
    }
    return;
  }
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const glm::dvec3 d = cube_texel_direction(face, n, i, j);
      inout.at(face, i, j) = trace_radiance(il, o, d, marcher);
    }
  }
}

void capture_face(const World& w, const glm::dvec3& p, CubeFace face, CubeMap& inout,
                  Marcher marcher) {
  capture_face(Illumination(w), p, face, inout, marcher);
}

CubeMap capture(const Illumination& il, const glm::dvec3& p, int face_size, Marcher marcher) {
  CubeMap m(face_size);
  for (int f = 0; f < kCubeFaces; ++f) capture_face(il, p, static_cast<CubeFace>(f), m, marcher);
  return m;
}

CubeMap capture(const World& w, const glm::dvec3& p, int face_size, Marcher marcher) {
  return capture(Illumination(w), p, face_size, marcher);
}

}  // namespace ambisim
