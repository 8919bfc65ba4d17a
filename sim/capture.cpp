#include "sim/capture.h"

#include <algorithm>
#include <cmath>

namespace ambisim {

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

void capture_face(const World& w, const glm::dvec3& p, CubeFace face, CubeMap& inout,
                  Marcher marcher) {
  const glm::dvec3 o = capture_origin(w, p);
  const int n = inout.size;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const glm::dvec3 d = cube_texel_direction(face, n, i, j);
      inout.at(face, i, j) = trace_radiance(w, o, d, marcher);
    }
  }
}

CubeMap capture(const World& w, const glm::dvec3& p, int face_size, Marcher marcher) {
  CubeMap m(face_size);
  for (int f = 0; f < kCubeFaces; ++f) capture_face(w, p, static_cast<CubeFace>(f), m, marcher);
  return m;
}

}  // namespace ambisim
