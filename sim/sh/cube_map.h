#pragma once
// HDR cube maps: six square faces of linear RGB radiance.
//
// Face order and texel directions (texel (i, j) of an N x N face, column i, row j, with
// u = 2 (i + 0.5) / N - 1 and v = 2 (j + 0.5) / N - 1, both in (-1, 1)):
//   +X: ( 1,  u,  v)    -X: (-1, -u,  v)
//   +Y: (-u,  1,  v)    -Y: ( u, -1,  v)
//   +Z: ( u,  v,  1)    -Z: ( u, -v, -1)
// (unnormalised; z is up, so row j grows upward on the four side faces).
#include <array>
#include <cstddef>
#include <vector>

#include <glm/vec3.hpp>

#include "sim/colour/rgb.h"

namespace ambisim {

enum class CubeFace : int { PosX = 0, NegX = 1, PosY = 2, NegY = 3, PosZ = 4, NegZ = 5 };
inline constexpr int kCubeFaces = 6;
inline constexpr std::array<const char*, kCubeFaces> kCubeFaceNames = {"+X", "-X", "+Y",
                                                                       "-Y", "+Z", "-Z"};

// Unnormalised direction through a point (u, v) in [-1, 1]^2 of a face.
glm::dvec3 cube_face_direction(CubeFace face, double u, double v);

// Unit direction through the centre of texel (i, j) of an N x N face.
glm::dvec3 cube_texel_direction(CubeFace face, int size, int i, int j);

// Exact solid angle of texel (i, j) of an N x N face (same for every face), from the
// closed-form area element atan2(u v, sqrt(u^2 + v^2 + 1)); all 6 N^2 texels sum to 4 pi.
double cube_texel_solid_angle(int size, int i, int j);

struct CubeMap {
  int size = 0;            // texels per face edge
  std::vector<Rgb> texel;  // [face][j][i], face-major, then row j, then column i

  CubeMap() = default;
  explicit CubeMap(int face_size)
      : size(face_size), texel(static_cast<std::size_t>(kCubeFaces) * face_size * face_size) {}

  std::size_t index(CubeFace f, int i, int j) const {
    return (static_cast<std::size_t>(f) * size + static_cast<std::size_t>(j)) * size +
           static_cast<std::size_t>(i);
  }
  Rgb& at(CubeFace f, int i, int j) { return texel[index(f, i, j)]; }
  const Rgb& at(CubeFace f, int i, int j) const { return texel[index(f, i, j)]; }
};

}  // namespace ambisim
