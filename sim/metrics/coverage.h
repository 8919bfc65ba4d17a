#pragma once
// Coverage: the share of demand points served by a probe within the spacing they need, without
// falling back (SPEC section 5).
//
// The rule. A probe lattice of spacing s seen from distance d subtends about s / d radians, so
// a fixed angular resolution needs s <= alpha d: alpha = 0.25 accepts gaps up to ~14 degrees
// (atan 0.25). Near the camera that would demand ever finer probes, so it is floored at s_min
// (4 m: objects and the lighting detail of the terrain around them are metres in size):
//   required_spacing(d) = max(s_min, alpha d),
//   served  <=>  !fell_back  &&  contributor_count > 0  &&  spacing_m <= required_spacing(d).
// contributor_count > 0 is the literal "served by a probe": a lookup that claims no fallback
// but names no probe is a planner bug and scores as unserved. spacing_m = +inf or NaN never
// passes. d is the straight-line (3D) distance from the camera.
//
// Demand points: the receivers (passed in by the simulator) plus ground points from
// demand_points(): rings around the camera, denser near it, and points ahead along the
// velocity, all a fixed height above the ground.
#include <functional>
#include <vector>

#include <glm/vec3.hpp>

#include "sim/planner.h"

namespace ambisim {

struct CoverageRule {
  double min_spacing_m = 4.0;   // s_min, > 0
  double spacing_per_m = 0.25;  // alpha, >= 0 (metres of probe gap per metre of distance)
};

// max(s_min, alpha d); d >= 0 in metres.
double required_spacing(double distance_m, const CoverageRule& rule);

// The rule above for one lookup at distance d >= 0 from the camera.
bool is_served(const LookupResult& lookup, double distance_m, const CoverageRule& rule);

struct DemandLayout {
  // Horizontal ring radii around the camera (m, > 0); denser near the camera by construction.
  std::vector<double> ring_radii_m{5.0, 10.0, 20.0, 40.0, 80.0, 160.0};
  int azimuths = 8;  // points per ring, >= 1, evenly spaced
  // Travel times ahead (s, >= 0): points at camera + horizontal velocity * t.
  std::vector<double> ahead_s{0.5, 1.0, 2.0, 4.0};
  double height_m = 1.5;  // above the ground (terrain, not canopy), >= 0
};

enum class DemandKind { receiver, ring, ahead };
const char* demand_kind_name(DemandKind kind);

struct DemandPoint {
  glm::dvec3 position{0.0};
  double distance_m = 0.0;  // 3D distance to the camera
  DemandKind kind = DemandKind::ring;
  friend bool operator==(const DemandPoint&, const DemandPoint&) = default;
};

// ring_radii_m.size() * azimuths + ahead_s.size() points, always (a static camera puts its
// ahead points below itself), in a fixed order: rings inner to outer, each starting at the
// heading and turning counter-clockwise (seen from above), then the ahead points by time.
// The heading is the horizontal velocity direction, or +x when the camera moves (nearly)
// vertically or not at all, so the layout is a pure function of its inputs.
// ground_height(x, y) is the terrain height in metres (z up).
std::vector<DemandPoint> demand_points(const glm::dvec3& camera_position,
                                       const glm::dvec3& camera_velocity,
                                       const std::function<double(double, double)>& ground_height,
                                       const DemandLayout& layout);

}  // namespace ambisim
