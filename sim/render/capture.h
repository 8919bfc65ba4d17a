#pragma once
// Cube-map captures of the world's radiance at a point (SPEC section 2). The sun disc is not
// rendered (it belongs to the direct term); dynamic objects are not part of the world.
//
// A capture point inside a column (below the surface, e.g. under the canopy) is lifted to
// kCaptureLift metres above that column's top, so every capture sees the scene from outside.
#include <glm/vec3.hpp>

#include "sim/render/ray_march.h"
#include "sim/sh/cube_map.h"
#include "sim/world/world.h"

namespace ambisim {

inline constexpr double kCaptureLift = 0.01;

// The point a capture at p actually renders from (p, or p lifted out of a column).
glm::dvec3 capture_origin(const World& w, const glm::dvec3& p);

// Renders all six faces, face_size x face_size texels each (face_size >= 1), in the light of
// `il` (its moment and layer; illumination.h), or of the world's own static lighting.
CubeMap capture(const Illumination& il, const glm::dvec3& p, int face_size,
                Marcher marcher = Marcher::accelerated);
CubeMap capture(const World& w, const glm::dvec3& p, int face_size,
                Marcher marcher = Marcher::accelerated);

// Renders one face into `inout` (which must already have the wanted size): the simulator
// captures one face per frame, each in the light of its own frame.
void capture_face(const Illumination& il, const glm::dvec3& p, CubeFace face, CubeMap& inout,
                  Marcher marcher = Marcher::accelerated);
void capture_face(const World& w, const glm::dvec3& p, CubeFace face, CubeMap& inout,
                  Marcher marcher = Marcher::accelerated);

}  // namespace ambisim
