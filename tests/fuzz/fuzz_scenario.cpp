// libFuzzer target: the scenario parser on arbitrary bytes read as JSON. Bad input must end in
// ambisim::InputError (or nlohmann's parse error for text that is not JSON); anything else
// escaping, a crash or a sanitizer report is a finding. A document the parser accepts must
// also build the records' cheap objects (frame schedule, budget, speed profile, keyframe
// path) without throwing: whatever the parser lets through, the simulator must be able to run.
#include <cstddef>
#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "sim/base/input_error.h"
#include "sim/scenario/camera_path.h"
#include "sim/scenario/capture_budget.h"
#include "sim/scenario/frame_schedule.h"
#include "sim/scenario/scenario.h"
#include "sim/scenario/speed_profile.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception&) {
    return 0;  // not JSON: load_json_file reports it with line and column
  }
  ambisim::Scenario s;
  try {
    s = ambisim::parse_scenario(doc, "fuzz.json");
  } catch (const ambisim::InputError&) {
    return 0;  // refused with a file and a path: the expected outcome for bad input
  }
  // Accepted: the pure record -> object constructions must succeed.
  const ambisim::FrameSchedule frames(s.frames);
  (void)frames.frame(frames.frame_count() > 0 ? frames.frame_count() - 1 : 0);
  const ambisim::CaptureBudget budget(s.budget);
  const ambisim::SpeedProfile speed(s.camera.speed);
  if (s.camera.type == ambisim::CameraPathRecord::Type::keyframes && !s.camera.z_above_ground) {
    const ambisim::CameraPath path(s.camera, ambisim::TerrainQueries{});
    (void)path.state(s.frames.duration_s, 0.0);
  }
  return 0;
}
