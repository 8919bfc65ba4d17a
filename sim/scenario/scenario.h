#pragma once
// A scenario file parsed into plain validated records (nothing is built here): the world, the
// camera path, the frame-rate schedule, the capture budget, the receivers, the metric settings
// and the reference settings. The schema is documented in scenarios/README.md.
#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "sim/metrics/metric_settings.h"
#include "sim/scenario/camera_path.h"
#include "sim/scenario/capture_budget.h"
#include "sim/scenario/frame_schedule.h"
#include "sim/scenario/receivers.h"
#include "sim/world/world_params.h"

namespace ambisim {

// How the reference irradiance (the truth a planner is scored against) is computed.
struct ReferenceSettings {
  int face_size = 24;       // cube face resolution of reference captures at receivers
  double interval_s = 0.0;  // 0: every frame; > 0: moving receivers sampled on this time grid
                            // and interpolated linearly in time between samples
  // A game's load: the reference and the scores cover every sample_stride-th receiver of each
  // kind in spawn order, from an offset per kind drawn from sample_seed (stratified systematic
  // sampling: equal odds for every receiver, spread over kinds and spawn times); the planner
  // still lights every receiver. 1: every receiver.
  int sample_stride = 1;
  std::uint64_t sample_seed = 1;
  double refine_de = 0.25;  // with interval_s > 0: a frame between two samples that differ by
                            // more is captured too, and its halves refined while linear
                            // interpolation mispredicts it by more (dE00)
};

struct Scenario {
  std::string file;  // where it was read from (for messages)
  std::string name;  // defaults to the file's stem
  std::string description;
  nlohmann::json document;  // the whole document as read (after sweep overrides)
  WorldParams world;
  CameraPathRecord camera;
  FrameScheduleRecord frames;
  CaptureBudgetRecord budget;
  ReceiversRecord receivers;
  MetricSettings metrics;
  ReferenceSettings reference;

  // Fingerprint of the whole document (any change in any section changes it) and of the
  // contents of the CSV recordings it names.
  std::uint64_t hash() const;
  // Fingerprint of what the reference depends on: everything but the capture budget. Runs
  // that differ only in budget or planner share one reference.
  std::uint64_t reference_hash() const;
};

// Parses a scenario document; `file` names it in errors. Unknown keys anywhere are errors.
Scenario parse_scenario(const nlohmann::json& document, const std::string& file);

// Loads and parses a scenario file.
Scenario load_scenario(const std::string& path);

class World;
// The checks that need the built world (the road's length, every landmark named); throws
// InputError naming the scenario file and the JSON path. Call before simulating.
void check_scenario_world(const Scenario& s, const World& world);

// The camera and receiver records with their landmark positions filled in from `world`
// (landmark_ref.h); throws InputError for a landmark the world lacks.
CameraPathRecord resolved_camera(const Scenario& s, const World& world);
ReceiversRecord resolved_receivers(const Scenario& s, const World& world);

// Sets a value inside a document at a JSON pointer ("/camera/speed_mps"), creating objects on
// the way; used by sweeps to vary one parameter. Throws InputError naming `file` if the path
// runs through a non-object.
void set_json_path(nlohmann::json& document, const std::string& pointer,
                   const nlohmann::json& value, const std::string& file);

std::string hex64(std::uint64_t v);

}  // namespace ambisim
