#pragma once
// The little a moving thing needs to know about the world: ground height and the road. The
// lead fills this from World; tests fill it with synthetic terrain. Keeping it this small
// lets camera paths and receivers be built and tested without a World.
#include <functional>

#include <glm/vec3.hpp>

#include "sim/world/spline.h"

namespace ambisim {

struct TerrainQueries {
  std::function<double(double, double)> ground_height;  // terrain without canopy (m), at (x, y)
  // Top of whatever is solid (terrain or forest canopy); receivers stand on it. Unset: ground.
  std::function<double(double, double)> surface_height;
  const Spline3* road = nullptr;  // road centre line at road-surface height, world coords
  double road_width = 0.0;        // full width of both carriageways (m)
};

// A point of a lane: `offset` metres to the right of the direction of travel (right-hand
// traffic: direction +1 follows increasing arc length), `height` metres above the road
// surface. The road cross-section is taken as level, so the lane is at the centre line's z.
// s is clamped to [0, road.length()]; direction is +1 or -1.
glm::dvec3 lane_point(const Spline3& road, double s, int direction, double offset, double height);

// d(lane_point)/ds by a central difference over +-0.5 m of arc (one-sided at the road ends):
// on a curve an offset lane is shorter or longer than the centre line by (1 -+ offset/R).
glm::dvec3 lane_derivative(const Spline3& road, double s, int direction, double offset);

// Unit vector pointing right of `forward` in the horizontal plane (z up); +x if `forward` is
// vertical or zero.
glm::dvec3 right_of(const glm::dvec3& forward);

}  // namespace ambisim
