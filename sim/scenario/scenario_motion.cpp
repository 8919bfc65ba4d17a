#include "sim/scenario/scenario_motion.h"

#include "sim/world/world_queries.h"

namespace ambisim {

ScenarioMotion::ScenarioMotion(const Scenario& scenario, const World& world)
    : terrain_(terrain_queries(world)),
      schedule_(scenario.frames),
      clock_(schedule_),
      camera_(scenario.camera, terrain_),
      receivers_(scenario.receivers, terrain_) {}

bool ScenarioMotion::next() {
  Frame f;
  if (!clock_.next(f)) return false;
  current_.frame = f;
  current_.camera = camera_.state(f.time, f.index == 0 ? f.time : previous_time_);
  previous_time_ = f.time;
  receivers_.update(f.time, current_.camera);
  return true;
}

}  // namespace ambisim
