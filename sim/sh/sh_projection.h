#pragma once
// Projection of a cube map of radiance onto the 9 real SH basis functions of sim/sh/sh9.h:
//   L_k = sum over texels t of L(t) Y_k(w_t) dOmega_t,
// with w_t the unit direction through the texel centre and dOmega_t its solid angle.
#include "sim/sh/cube_map.h"
#include "sim/sh/sh9.h"

#include <vector>

namespace ambisim {

// exact_solid_angle: dOmega_t from cube_texel_solid_angle (sums to 4 pi).
// uniform_thesis: the thesis' 4 pi / (6 N^2) for every texel. It over-weights the face corners
// (up to 3^{3/2} = 5.2x their true solid angle) and is kept only to measure that error.
enum class TexelWeighting { exact_solid_angle, uniform_thesis };

// Quadrature weight of texel (i, j) of an N x N face (the same on all six faces).
double texel_weight(int size, int i, int j, TexelWeighting weighting);

// Slow reference: per texel direction, basis and weight in double. cube.size >= 1.
Sh9Rgb project_cube_naive(const CubeMap& cube,
                          TexelWeighting weighting = TexelWeighting::exact_solid_angle);

// Fast projection with precomputed float tables of weight * Y_k. For even N the table is
// folded by the mirror symmetries of each face (each Y_k is even or odd in u and in v on
// every face), so four texels share one 9-entry table row: 4x fewer multiply-adds.
class ShProjector {
 public:
  // face_size >= 1; throws std::invalid_argument otherwise.
  explicit ShProjector(int face_size, TexelWeighting weighting = TexelWeighting::exact_solid_angle);

  // cube.size must equal face_size() (std::invalid_argument otherwise).
  Sh9Rgb project(const CubeMap& cube) const;

  // Adds one face's contribution to acc; summing all six faces in order equals project()
  // bit for bit (the simulator renders and projects one face per frame).
  void accumulate_face(const CubeMap& cube, CubeFace face, Sh9Rgb& acc) const;

  int face_size() const { return size_; }
  TexelWeighting weighting() const { return weighting_; }

 private:
  void check(const CubeMap& cube) const;

  int size_;
  TexelWeighting weighting_;
  // Even sizes: [face][quad (j, i) of the lower-left quadrant][slot 0..8], slots ordered by
  // parity class (0-3 even/even, 4-5 odd in u, 6-7 odd in v, 8 odd/odd).
  std::vector<float> folded_;
  std::array<std::array<int, kShCount>, kCubeFaces> slot_to_k_{};
  // Odd sizes: [face][texel j * N + i][k].
  std::vector<float> dense_;
};

// Shared projector per (size, weighting), built once and kept for the process lifetime.
// Thread-safe; the returned reference stays valid.
const ShProjector& projector_for(int face_size,
                                 TexelWeighting weighting = TexelWeighting::exact_solid_angle);

}  // namespace ambisim
