#include "sim/scenario/scenario_motion.h"

#include <cmath>

#include <glm/geometric.hpp>

#include "sim/world/world_queries.h"

namespace ambisim {

ScenarioMotion::ScenarioMotion(const Scenario& scenario, const World& world)
    : terrain_(terrain_queries(world)),
      schedule_(scenario.frames),
      clock_(schedule_),
      camera_(resolved_camera(scenario, world), terrain_),
      receivers_(resolved_receivers(scenario, world), terrain_),
      view_(scenario.camera.view) {
  if (scenario.camera.look_at) look_at_ = resolved_camera(scenario, world).look_at;
}

bool ScenarioMotion::next() {
  Frame f;
  if (!clock_.next(f)) return false;
  current_.frame = f;
  current_.camera = camera_.state(f.time, f.index == 0 ? f.time : previous_time_);
  previous_time_ = f.time;
  receivers_.update(f.time, current_.camera);
  const glm::dvec3 look =
      look_at_ ? *look_at_ - current_.camera.position : current_.camera.velocity;
  const double len = glm::length(look);
  if (len > 1e-9 && std::isfinite(len)) current_.look = look / len;
  return true;
}

std::vector<CameraSample> record_camera(const Scenario& scenario, const World& world) {
  ScenarioMotion motion(scenario, world);
  std::vector<CameraSample> out;
  out.reserve(static_cast<std::size_t>(motion.frame_count()));
  while (motion.next()) {
    const CameraState& c = motion.current().camera;
    out.push_back({motion.current().frame.time, c.position, c.velocity, c.cut});
  }
  return out;
}

}  // namespace ambisim
