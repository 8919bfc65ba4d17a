#pragma once
// Named places in a generated world for scenario design: where a "fast flight toward a
// forest edge" can start, where the road runs through its deepest cutting and over its highest
// embankment, the most prominent rock outcrop and the highest cliff. Found by deterministic
// scans of the public World queries (World::landmarks() keeps them), so a scenario that names
// a landmark instead of coordinates runs on any world seed.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

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

// A rock outcrop: a rock-covered high point that stands out of its surroundings.
struct OutcropLandmark {
  bool found = false;
  glm::dvec3 top{0.0};        // ground there
  double prominence_m = 0.0;  // above the mean ground 80 m around
};

// A cliff: the top of the highest drop of the ground over a short distance.
struct CliffLandmark {
  bool found = false;
  glm::dvec3 top{0.0};        // the ground at the edge, on the high side
  glm::dvec2 direction{0.0};  // unit, over the edge (downhill)
  double drop_m = 0.0;        // ground fall within 16 m past the edge
};

struct WorldLandmarks {
  ForestEdgeApproach forest_edge;
  RoadLandmark deepest_cutting;
  RoadLandmark highest_embankment;
  glm::dvec2 deepest_cutting_tangent{1.0, 0.0};  // horizontal road direction there
  glm::dvec2 highest_embankment_tangent{1.0, 0.0};
  OutcropLandmark rock_outcrop;
  CliffLandmark cliff;
};

// Forest edge: the longest straight run (up to 400 m) of open ground (grass, field, sand)
// rising at most 10 m that ends in forest at least 60 m deep, searched on a 32 m grid in 8
// directions at least 200 m from the border, with the edge at least 500 m (a fifth of a small
// world's side) from it. Road: sampled every 8 m, relief measured 20 m
// beyond the graded verge on both sides (both sides above: cutting; both below: embankment).
// Rock outcrop: on a 16 m grid at least 300 m from the border, the rock cell whose ground
// stands highest above the mean of 16 points 80 m around it (at least 15 m). Cliff: on an 8 m
// grid at least 300 m from the border and off the road, in 8 directions, the largest drop of the
// ground from a point to the point 16 m farther (at least 20 m), on open or rock ground.
WorldLandmarks find_landmarks(const World& w);

// A landmark as a place and a frame for offsets: `origin` (z = the ground there), `along` (a
// horizontal unit vector: toward the forest, along the road, over the cliff edge; +x for the
// outcrop), `left` = along turned 90 degrees counter-clockwise, up = +z.
struct LandmarkFrame {
  glm::dvec3 origin{0.0};
  glm::dvec2 along{1.0, 0.0};
  // origin + offset.x along + offset.y left + offset.z up.
  glm::dvec3 point(const glm::dvec3& offset) const;
};

// The names a scenario may use, in a fixed order: forest_edge, road.deepest_cutting,
// road.highest_embankment, rock_outcrop, cliff.
const std::vector<std::string>& landmark_names();
bool is_landmark_name(std::string_view name);
// The landmark's frame in this world; nullopt when the world has none (no road, no forest
// edge, ...). `name` must be one of landmark_names().
std::optional<LandmarkFrame> landmark_frame(const WorldLandmarks& landmarks, std::string_view name);

}  // namespace ambisim
