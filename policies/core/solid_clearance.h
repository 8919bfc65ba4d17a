#pragma once
// A capture point out of terrain and canopy (thesis L318): a cube map rendered inside a hill
// or a crown sees its backfaces, and its light would be attributed to a point nobody stands
// at. Planners that capture where the camera is (which may fly through crowns) move the point
// straight up to `clearance_m` above the surface; lattice planners decide per cell whether to
// move a probe by at most half a cell or drop it.
#include <algorithm>

#include <glm/vec3.hpp>

#include "sim/planner.h"

namespace ambisim {

// Where camera-position planners capture: 0.3 m above the surface at least.
inline constexpr double kSolidClearance_m = 0.3;

// `p` moved up to at least clearance_m above surface_height (ground_height without one);
// unchanged without a world.
inline glm::dvec3 above_solids(const WorldQueries* world, glm::dvec3 p, double clearance_m) {
  if (world == nullptr) return p;
  if (world->surface_height) {
    p.z = std::max(p.z, world->surface_height(p.x, p.y) + clearance_m);
  } else if (world->ground_height) {
    p.z = std::max(p.z, world->ground_height(p.x, p.y) + clearance_m);
  }
  return p;
}

}  // namespace ambisim
