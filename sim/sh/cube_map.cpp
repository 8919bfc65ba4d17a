#include "sim/sh/cube_map.h"

#include <cmath>

#include <glm/geometric.hpp>

namespace ambisim {
namespace {

// Integral of the solid-angle density 1/(1+u^2+v^2)^{3/2} over [0,u]x[0,v] (signed).
double area_element(double u, double v) {
  return std::atan2(u * v, std::sqrt(u * u + v * v + 1.0));
}

double texel_coord(int size, int k) { return 2.0 * (k + 0.5) / size - 1.0; }

}  // namespace

glm::dvec3 cube_face_direction(CubeFace face, double u, double v) {
  switch (face) {
    case CubeFace::PosX:
      return {1.0, u, v};
    case CubeFace::NegX:
      return {-1.0, -u, v};
    case CubeFace::PosY:
      return {-u, 1.0, v};
    case CubeFace::NegY:
      return {u, -1.0, v};
    case CubeFace::PosZ:
      return {u, v, 1.0};
    case CubeFace::NegZ:
      return {u, -v, -1.0};
  }
  return {0.0, 0.0, 1.0};
}

glm::dvec3 cube_texel_direction(CubeFace face, int size, int i, int j) {
  return glm::normalize(cube_face_direction(face, texel_coord(size, i), texel_coord(size, j)));
}

double cube_texel_solid_angle(int size, int i, int j) {
  const double x0 = 2.0 * i / size - 1.0, x1 = 2.0 * (i + 1) / size - 1.0;
  const double y0 = 2.0 * j / size - 1.0, y1 = 2.0 * (j + 1) / size - 1.0;
  return area_element(x0, y0) - area_element(x0, y1) - area_element(x1, y0) + area_element(x1, y1);
}

}  // namespace ambisim
