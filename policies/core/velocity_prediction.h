#pragma once
// Velocity prediction (thesis 8.1, 7.5.3), shared by the `+vp` planners: plan around where the
// camera will be when a capture started now becomes usable, plus a look-ahead, and stretch the
// high-resolution region along the motion. `route` uses the road spline as the game's
// knowledge of where a car is going (thesis 7.5.3) instead of a straight line.
#include <algorithm>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "sim/planner.h"

namespace ambisim {

struct PredictionSettings {
  bool enabled = false;
  double lookahead_s = 0.5;    // beyond the capture latency
  bool route = false;          // follow the road spline when the camera is on it
  double route_snap_m = 15.0;  // "on the road": within this distance of the centre line
};

// Where the planner should focus: a segment from the camera to its predicted position. With
// prediction off, both ends are the camera.
struct Focus {
  glm::dvec3 now{0.0};
  glm::dvec3 ahead{0.0};
  // Distance from p to the focus segment: the "distance to the camera" a planner refines by.
  // Inline: planners call it once or twice per probe per frame.
  double distance(const glm::dvec3& p) const {
    const glm::dvec3 d = ahead - now;
    const double len2 = glm::dot(d, d);
    if (len2 <= 0.0) return glm::length(p - now);
    const double t = std::clamp(glm::dot(p - now, d) / len2, 0.0, 1.0);
    return glm::length(p - (now + t * d));
  }
};

// Predicted position after `horizon_s` seconds: straight-line, or along the road.
glm::dvec3 predict_position(const FrameContext& ctx, double horizon_s, bool route,
                            double route_snap_m);

// Points every spacing_m along the road from the camera's closest point to ahead_s seconds
// ahead at its speed along the road, keeping its offset from the centre line; empty off the
// road (farther than route_snap_m from it) or without one. What a game knows of where a car
// goes (thesis L316).
std::vector<glm::dvec3> road_ahead(const FrameContext& ctx, double ahead_s, double spacing_m,
                                   double route_snap_m);

// The focus for this frame. Horizon = ctx.capture_latency_s() + lookahead_s; on a camera cut
// the prediction is dropped for that frame (the velocity says nothing about the jump).
Focus make_focus(const FrameContext& ctx, const PredictionSettings& s);

}  // namespace ambisim
