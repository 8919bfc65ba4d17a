#pragma once
// Everything in a scenario that moves independently of the planner: the frame clock, the
// camera and the receivers. The reference pass and every planner's run step the same motion,
// so they see identical frames, camera states and receivers by construction.
#include <optional>

#include "sim/scenario/camera_path.h"
#include "sim/scenario/frame_schedule.h"
#include "sim/scenario/receivers.h"
#include "sim/scenario/recorded_track.h"
#include "sim/scenario/scenario.h"
#include "sim/world/terrain_queries.h"

namespace ambisim {

class World;

struct MotionFrame {
  Frame frame;
  CameraState camera;
  // Where the player's view looks (unit): at the scenario's look_at, else along the camera's
  // velocity, else where it looked last (+x before the camera ever moved).
  glm::dvec3 look{1.0, 0.0, 0.0};
};

class ScenarioMotion {
 public:
  ScenarioMotion(const Scenario& scenario, const World& world);
  ScenarioMotion(const ScenarioMotion&) = delete;
  ScenarioMotion& operator=(const ScenarioMotion&) = delete;

  // Advances to the next frame; false after the last one.
  bool next();
  const MotionFrame& current() const { return current_; }
  const std::vector<Receiver>& receivers() const { return receivers_.live(); }
  std::int64_t frame_count() const { return schedule_.frame_count(); }
  const FrameSchedule& schedule() const { return schedule_; }
  const ViewSpec& view() const { return view_; }
  const CameraPath& camera_path() const { return camera_; }

 private:
  TerrainQueries terrain_;
  FrameSchedule schedule_;
  FrameClock clock_;
  CameraPath camera_;
  ReceiverSet receivers_;
  MotionFrame current_;
  double previous_time_ = 0.0;
  ViewSpec view_;
  std::optional<glm::dvec3> look_at_;
};

// The camera of every frame of `scenario` (time, position, velocity, cut), as a recording:
// camera_csv() of it replays through a "recorded" camera with the same position, velocity and
// cut at every frame time.
std::vector<CameraSample> record_camera(const Scenario& scenario, const World& world);

}  // namespace ambisim
