#pragma once
// The referee: flies the scenario's camera, grants captures within the budget, lights the
// receivers through a planner and scores the result (SPEC section 3).
//
// Per frame, in this order:
//   0. before the first frame only: the planner's preload captures are rendered and delivered
//      outside the budget (a bake; counted as bake.* in the summary), each in frame 0's light
//      or in that of its CaptureRequest::time (in time order; frame 0's light is restored);
//   1. the motion advances (camera, receivers);
//   2. the planner sees the receivers and plans; the simulator starts at most
//      `startable_captures` requests (the budget's free faces after those owed to captures in
//      flight) and refuses the rest;
//   3. granted faces are rendered, oldest capture first (a probe takes 6 faces: at the default
//      1 face per frame, 6 frames, while the camera keeps moving);
//   4. the planner updates (lifetimes, fades);
//   5. every live receiver and every coverage demand point is looked up and scored;
//   6. probes whose sixth face was rendered this frame are projected and delivered: usable from
//      the next frame.
// A planner that ignores the budget (the oracle) gets every request rendered and delivered at
// once, before its lookups.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sim/metrics/metrics.h"
#include "sim/metrics/view_weights.h"
#include "sim/planner.h"
#include "sim/run/reference_track.h"
#include "sim/scenario/scenario.h"

namespace ambisim {

class World;

// Measured, not simulated: wall-clock costs, reported apart from the deterministic results.
struct RunTiming {
  double total_s = 0.0;
  double planner_s = 0.0;  // plan + update + deliver
  double lookup_s = 0.0;
  std::int64_t lookups = 0;
  double capture_s = 0.0;  // face rendering and projection
  double bake_s = 0.0;     // the planner's preload captures, before the first frame
  std::int64_t frames = 0;
  nlohmann::ordered_json to_json() const;
};

// The state of a run at one moment, for the VTK views: the planner's nodes, the camera and the
// receivers (with the planner's and the reference's irradiance straight up, for colouring).
struct Snapshot {
  std::int64_t frame = 0;
  double time = 0.0;
  glm::dvec3 camera{0.0};
  std::vector<ProbeNodeView> nodes;
  std::vector<glm::dvec3> receivers;
  // Per receiver (same order; empty without a reference): the planner's and the reference's
  // irradiance (the reference capture in SH9) straight up and toward the camera, the displayed
  // CIEDE2000 between the two toward the camera, and whether it popped where seen this frame.
  struct ReceiverLight {
    Rgb planner_up, reference_up, planner_view, reference_view;
    double de2000_view = 0.0;
    bool viewed_pop = false;
  };
  std::vector<ReceiverLight> light;
};

struct RunResult {
  Summary summary;
  std::vector<FrameRow> frames;
  RunTiming timing;
  std::int64_t captures_started = 0;
  std::int64_t captures_delivered = 0;
  double exposure = 0.0;
  // What the reference cost (0 without one): captures rendered, receiver-frames it serves,
  // and how many of those were interpolated in time rather than captured.
  std::int64_t reference_captures = 0;
  std::int64_t reference_slots = 0;
  std::int64_t reference_interpolated = 0;
  std::vector<glm::dvec3> camera_path;  // camera position per frame
  std::vector<Snapshot> snapshots;
};

// At most this many snapshots per run: longer runs space them out.
inline constexpr double kMaxSnapshots = 120.0;

// One live receiver of a frame as the referee scored it, for tools that show a run
// (`ambisim film`): what the planner answered, the reference's SH9 at the same slot, and
// whether it popped where the player sees it.
struct ObservedReceiver {
  std::uint64_t id = 0;
  glm::dvec3 position{0.0};
  double size_m = 0.0;  // diameter of the sphere a player sees
  Sh9Rgb planner_sh;    // the planner's lookup
  Sh9Rgb reference_sh;  // the reference capture in SH9 (the oracle's answer)
  double screen_weight = 0.0;
  bool viewed_pop = false;  // counted in pops.viewed this frame
};

// A scored frame: the camera as the player's view sees it, every live receiver (id order) and
// the frame's row of the per-frame series.
struct FrameObservation {
  std::int64_t frame = 0;
  double time = 0.0;
  glm::dvec3 camera{0.0};
  glm::dvec3 look{1.0, 0.0, 0.0};
  bool camera_cut = false;
  ViewSpec view;
  std::vector<ObservedReceiver> receivers;
  FrameRow row;
};

struct SimulationOptions {
  bool keep_frames = true;        // keep the per-frame series
  double snapshot_every_s = 1.0;  // record a Snapshot this often (0: never)
  // Called once per frame after it is scored (simulate() with a reference only); empty:
  // nothing is gathered. It only reads, so a run with an observer scores the same.
  std::function<void(const FrameObservation&)> on_frame;
};

// How the player's view sees receiver r: its screen weight (a sphere of r.size_m) and the
// direction to the camera (view_weights.h).
ReceiverViewing receiver_viewing(const CameraView& view, const Receiver& r);

class ScenarioMotion;
// Where the camera goes during the run, as its positions at the frames kept at least spacing_m
// apart, and the last (the "route" the planners are told about: the level's playable path).
std::vector<glm::dvec3> camera_route(const ScenarioMotion& motion, double spacing_m);
// The centres of the cell_m x cell_m squares (x, y) the receivers visit at the run's frames,
// in ascending (i, j) order, z the first visitor's height (WorldQueries::object_cells). Steps
// its own motion, so the run's is untouched.
std::vector<glm::dvec3> object_cells(const Scenario& scenario, const World& world, double cell_m);

RunResult simulate(const Scenario& scenario, const World& world, const ReferenceTrack& reference,
                   Planner& planner, const SimulationOptions& options = {});

// The same run without a reference track ("reference off"), for throughput measurements and
// for tools that only need what the planner did. Everything the planner sees and does is
// identical to simulate(): the frames, the budget, plan/started/refused/update/deliver, every
// receiver and demand-point lookup, the rendered captures. What needs the reference is left
// out: no irradiance is evaluated at the metric normals and nothing is scored against truth, so
// the summary's accuracy, pops, staleness and receiver counts stay empty (0 or NaN) and
// `exposure` is 0; faces, captures, probes, memory and coverage are the same as with it.
// The oracle is served from the reference, so it throws std::invalid_argument here.
RunResult simulate_without_reference(const Scenario& scenario, const World& world, Planner& planner,
                                     const SimulationOptions& options = {});

}  // namespace ambisim
