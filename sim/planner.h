#pragma once
// The one interface every sampling planner implements (OMPL-style: the simulator, the sweep
// and the shared contract test only ever see this). Implementations live in policies/.
//
// Before the first frame: preload(ctx) -> captures rendered outside the budget, as a game does
// at load time (a bake); delivered before frame 0 and counted apart (bake.*). Most return none.
// The contract, per frame (see sim/run/simulator.cpp):
//   1. plan(ctx)      -> capture requests in priority order. The simulator starts at most
//                        ctx.startable_captures of them, in order; each one it does not start
//                        is refused (counted, and reported through refused()).
//   2. started(tag)   <- for each request the simulator actually starts.
//   3. update(ctx)       lifetimes, fades, pruning (the only place time moves for a planner).
//   4. lookup(p)         interpolated coefficients for a receiver, any number of times
//      (lookup_many: all of a frame's points in one call, the same results).
//   5. deliver(probe) <- probes whose six faces are all rendered (usable from the next frame).
// The frame context is the only clock. A planner never sees the reference solution.
#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include "sim/colour/rgb.h"
#include "sim/sh/sh9.h"

namespace ambisim {

class Spline3;

// What an engine knows of its own lighting at a time: its time of day and weather state, never
// the lighting solution at a point.
struct LightingInfo {
  glm::dvec3 sun_dir{0.0, 0.0, 1.0};  // toward the sun
  bool sun_on = false;
  Rgb sun_irradiance{0.0f};  // on a plane facing the sun
  Sh9Rgb sky_sh;             // the sky's radiance (clouds at their mean cover), zero below
  double lamp_level = 0.0;   // street lamps: 0 off, 1 on
  // How fast the lighting changes anywhere (1/s): the largest relative rate of the sun's and
  // the sky's brightness, the sun's angular speed (rad/s) and the fog's density...
  double sun_sky_change_rate = 0.0;
  // ... and 1/s within 0.5 s of a lamp switch (a switch changes the light near the lamps by
  // about all of the lamps' share: drift integrates to 1 over the switch)...
  double lamp_change_rate = 0.0;
  // ... and the larger of the two: the thesis' "maximum rate at which the light can change".
  // Cloud drift is local: WorldQueries::lighting_change_at.
  double change_rate = 0.0;
};

// World knowledge a game engine legitimately has (never the lighting solution).
struct WorldQueries {
  std::function<double(double, double)> ground_height;   // terrain, without canopy
  std::function<double(double, double)> surface_height;  // terrain or canopy top
  const Spline3* road = nullptr;                         // may be null
  glm::dvec3 bounds_min{0.0};
  glm::dvec3 bounds_max{0.0};
  // The lighting at a time (the frame's own time, or any other: an engine knows its time-of-day
  // schedule); and how fast it changes at a point (the global rate and the local cloud drift).
  std::function<LightingInfo(double)> lighting;
  // The local rate at a point without the lamps (the sun's, the sky's, the fog's and the cloud
  // shadows drifting over it; 1/s): LightingInfo::sun_sky_change_rate or more.
  std::function<double(const glm::dvec3&, double)> lighting_change_at;
  bool lighting_static = true;  // nothing ever changes: lifetimes can be infinite
  bool has_lamps = false;       // the world has street lamps (lamp layers are worth capturing)
  // Where the lamps stand and how far their light reaches across the ground (an engine knows
  // its lights and their attenuation ranges).
  std::vector<glm::dvec3> lamp_positions;
  double lamp_reach_m = 0.0;
  // The level's playable route: where the camera can go (a race track, a road, the designed
  // path), as points about 10 m apart. What a team bakes its static lighting around.
  std::vector<glm::dvec3> route;
  // Where the level's lit objects go besides (the traffic's lanes, a player's aircraft): the
  // centres of the object_cell_m squares (x, y) they visit during the run, in ascending cell
  // order. A bake covers these too: a studio bakes the whole drivable level, not only the
  // player's own path.
  std::vector<glm::dvec3> object_cells;
  double object_cell_m = 0.0;
};

struct FrameContext {
  std::int64_t frame = 0;
  double time = 0.0;  // seconds since the start; the only clock a planner sees
  double dt = 0.0;    // this frame's step
  glm::dvec3 camera_position{0.0};
  glm::dvec3 camera_velocity{0.0};
  bool camera_cut = false;       // the camera teleported this frame
  double faces_per_frame = 1.0;  // the capture budget (cube faces per frame)
  int face_size = 16;            // cube face resolution of captures
  int startable_captures = 0;    // how many new captures plan() may start this frame
  // The run's length in seconds, known from the start: the time span a level's lighting is
  // baked for (its time-of-day window), as a game knows its own schedule.
  double run_duration_s = 0.0;
  const WorldQueries* world = nullptr;
  // Frames from a capture's start until it is usable, at the current budget: ceil(6 / faces).
  double capture_latency_s() const;
};

struct CaptureRequest {
  glm::dvec3 position{0.0};
  std::uint64_t tag = 0;  // the planner's own id for this capture; echoed on delivery
  // Also render the street lamps' light apart (thesis 7.5.3: an additive set scaled by the
  // lamps' state): 12 faces instead of 6; `sh` is then everything but the lamps.
  bool lamp_layer = false;
  // Preload only: render this capture in the light of this time (s since the start) instead of
  // frame 0's, e.g. a bake at several times of day. Negative: frame 0's light. The simulator
  // renders preload captures in time order and delivers them in that order (stable: requests
  // of the same time keep the planner's order); a request from plan() with a time >= 0 is a
  // contract violation (std::logic_error).
  double time = -1.0;
  // Preload only: render at this cube-face resolution instead of the budget's (a bake is
  // rendered offline, at the quality a studio ships). 0: the budget's; a request from plan()
  // with a face size is a contract violation (std::logic_error).
  int face_size = 0;
};

struct FinishedProbe {
  std::uint64_t tag = 0;
  glm::dvec3 position{0.0};
  Sh9Rgb sh;  // all the light at its faces' times (or all but the lamps, with a lamp layer)
  double requested_time = 0.0;
  double finished_time = 0.0;
  bool has_lamp_layer = false;
  Sh9Rgb sh_lamps{};  // the lamps alone at full power (with a lamp layer)
};

// Which stored probes contributed to a lookup, for coverage and staleness.
struct Contributor {
  std::uint64_t tag = 0;
  float weight = 0.0f;
};

struct LookupResult {
  Sh9Rgb sh;
  std::array<Contributor, 8> contributors{};
  int contributor_count = 0;
  bool fell_back = false;  // no probe served this point (a default/coarse answer)
  double spacing_m = 0.0;  // the spacing of the probes used (0 = exact, inf = none)
  double data_time = 0.0;  // capture time of the (weighted) data used, for staleness
};

// The points of a batch lookup as a structure of arrays (every receiver of a frame): a planner
// that sorts or vectorises its lookups reads the coordinates it needs contiguously.
struct LookupPoints {
  std::vector<double> x, y, z;
  std::size_t size() const { return x.size(); }
  void clear() {
    x.clear();
    y.clear();
    z.clear();
  }
  void reserve(std::size_t n) {
    x.reserve(n);
    y.reserve(n);
    z.reserve(n);
  }
  void push_back(const glm::dvec3& p) {
    x.push_back(p.x);
    y.push_back(p.y);
    z.push_back(p.z);
  }
  glm::dvec3 at(std::size_t i) const { return {x[i], y[i], z[i]}; }
};

// One node (or probe) of a planner's structure, for the VTK views: where it is, how big, and
// what it holds. Planners without a spatial structure report their probes as zero-size nodes.
struct ProbeNodeView {
  glm::dvec3 centre{0.0};
  glm::dvec3 half_extent{0.0};  // half the node's size per axis (0 for a bare probe)
  int depth = 0;
  bool has_data = false;   // holds usable coefficients
  bool in_flight = false;  // a capture for it is being rendered
  double age_s = 0.0;      // time since its data was captured
  Sh9Rgb sh;               // the coefficients it holds (zero when it holds none)
};

struct PlannerStats {
  std::int64_t live_probes = 0;  // coefficient sets held
  std::int64_t nodes = 0;        // structure nodes (0 if the planner has none)
  std::int64_t bytes = 0;        // memory held by coefficients and structure
};

class Planner {
 public:
  virtual ~Planner() = default;
  virtual std::string name() const = 0;
  virtual nlohmann::json params() const = 0;  // every parameter, echoed into results

  // Captures to render before the first frame without budget (ctx is frame 0's context). The
  // simulator renders each at ctx.face_size in frame 0's light (or that of its `time`),
  // delivers it (requested and finished at time 0, whatever light it was rendered in) and
  // reports the count and the faces as the run's bake cost. Default: none.
  virtual std::vector<CaptureRequest> preload(const FrameContext& /*ctx*/) { return {}; }
  virtual std::vector<CaptureRequest> plan(const FrameContext& ctx) = 0;
  virtual void started(std::uint64_t tag) = 0;
  virtual void refused(std::uint64_t /*tag*/) {}
  virtual void deliver(const FinishedProbe& probe) = 0;
  virtual void update(const FrameContext& ctx) = 0;
  virtual LookupResult lookup(const glm::dvec3& p) const = 0;
  // Every point of a frame at once: out[i] must equal lookup(points.at(i)) exactly (the
  // contract test checks it). The simulator uses this one. Default: a loop over lookup().
  virtual void lookup_many(const LookupPoints& points, std::vector<LookupResult>& out) const {
    out.resize(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) out[i] = lookup(points.at(i));
  }
  virtual PlannerStats stats() const = 0;

  // Per-receiver capture planners (per_object, oracle) need to know the receivers.
  struct ReceiverView {
    std::uint64_t id;
    glm::dvec3 position;
    glm::dvec3 velocity;
  };
  virtual void set_receivers(const std::vector<ReceiverView>& /*receivers*/) {}
  // True for the oracle: the simulator captures at every lookup point without budget.
  virtual bool ignores_budget() const { return false; }
  // The structure for views (VTK), at the current time. Optional.
  virtual void describe_nodes(std::vector<ProbeNodeView>& /*out*/) const {}
};

}  // namespace ambisim
