#pragma once
// Named places in a generated world for scenario design: where a "fast flight toward a
// forest edge" can start, and where the road runs through its deepest cutting and over its
// highest embankment. Found by deterministic scans of the public World queries.
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "sim/world/world.h"

namespace ambisim {

struct ForestEdgeApproach {
  bool found = false;
  glm::dvec3 start{0.0};      // on open, flat ground (z = ground height)
  glm::dvec2 direction{0.0};  // unit, toward the edge
  double distance_m = 0.0;    // open ground from start to the first canopy cell
  glm::dvec3 edge{0.0};       // first canopy point (z = ground height there)
};

struct RoadLandmark {
  bool found = false;
  double s = 0.0;         // arc length along World::road()
  glm::dvec3 point{0.0};  // road surface there
  double relief_m = 0.0;  // terrain above (cutting, > 0) or below (embankment, < 0) the road
};

struct WorldLandmarks {
  ForestEdgeApproach forest_edge;
  RoadLandmark deepest_cutting;
  RoadLandmark highest_embankment;
};

// Forest edge: the longest straight run (up to 400 m) of open ground (grass, field, sand)
// rising at most 10 m that ends in forest at least 60 m deep, searched on a 32 m grid in 8
// directions at least 200 m from the border. Road: sampled every 8 m, relief measured 20 m
// beyond the graded verge on both sides (both sides above: cutting; both below: embankment).
WorldLandmarks find_landmarks(const World& w);

}  // namespace ambisim
