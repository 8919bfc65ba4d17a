#pragma once
// Terrain shadows from a directional sun: the shadow-height map S(c) of a column grid, so that a
// point above cell c is sunlit iff its z >= S(c). One sweep away from the sun in O(cells):
// S(c) = max(H(q), S(q)) - |q - c| tan(elevation), q one cell toward the sun along the dominant
// axis (linear interpolation across the other axis). kNoShadow where nothing can shadow, +inf
// everywhere when the sun is off (below the horizon).
#include <limits>
#include <vector>

#include <glm/vec3.hpp>

#include "sim/world/height_pyramid.h"

namespace ambisim {

inline constexpr float kNoShadow = HeightPyramid::kEmpty;

// surface: nx * ny column tops, row-major (index j * nx + i); sun_dir unit, toward the sun.
std::vector<float> shadow_heights(const std::vector<float>& surface, int nx, int ny, double cell_m,
                                  const glm::dvec3& sun_dir, bool sun_on);

}  // namespace ambisim
