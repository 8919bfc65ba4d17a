#pragma once
// Reference irradiance from a cube map, without SH truncation: the cube is read as piecewise
// constant radiance (each texel uniform over its spherical quad) and
//   E(n) = sum over texels t of L_t * integral over t of max(0, n . w) dOmega,
// where the per-texel integral is exact (texel quad clipped to the hemisphere n . w >= 0, then
// Lambert's polygon formula), not the texel-centre rule max(0, n . w_t) dOmega_t. So a
// constant cube gives pi L and a horizon-aligned sky/ground cube gives the closed form to
// rounding; the remaining error is only that of the cube's texel-constant radiance.
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "sim/colour/rgb.h"
#include "sim/sh/cube_map.h"

namespace ambisim {

// Exact integral of max(0, n . w) over the solid angle of texel (i, j) of an N x N face.
// unit_normal must be normalised; result in [0, cube_texel_solid_angle(size, i, j)].
double texel_cosine_integral(CubeFace face, int size, int i, int j, const glm::dvec3& unit_normal);

// Slow, direct reference for one normal (double accumulation). cube.size >= 1.
Rgb exact_irradiance(const CubeMap& cube, const glm::dvec3& unit_normal);

// The same for a fixed set of normals, with the per-normal texel weights precomputed once
// (only texels in each normal's hemisphere are stored). Results in the order of the normals.
class IrradianceIntegrator {
 public:
  // face_size >= 1, normals unit length (std::invalid_argument otherwise).
  IrradianceIntegrator(int face_size, std::vector<glm::dvec3> unit_normals);

  // cube.size must equal face_size().
  std::vector<Rgb> integrate(const CubeMap& cube) const;

  int face_size() const { return size_; }
  const std::vector<glm::dvec3>& normals() const { return normals_; }

 private:
  int size_;
  std::vector<glm::dvec3> normals_;
  std::vector<std::size_t> begin_;    // entries of normal m: [begin_[m], begin_[m + 1])
  std::vector<std::uint32_t> texel_;  // index into CubeMap::texel
  std::vector<double> weight_;        // texel_cosine_integral of that texel
};

}  // namespace ambisim
