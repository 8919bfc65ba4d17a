#include "sim/world/world_queries.h"

#include "sim/world/lighting_model.h"

namespace ambisim {

TerrainQueries terrain_queries(const World& world) {
  TerrainQueries q;
  q.ground_height = [&world](double x, double y) { return world.ground_height(x, y); };
  q.surface_height = [&world](double x, double y) { return world.surface_height(x, y); };
  q.road = world.road().empty() ? nullptr : &world.road();
  q.road_width = world.road_width_m();
  return q;
}

WorldQueries planner_world_queries(const World& world, LightingModel* lighting) {
  WorldQueries q;
  if (lighting != nullptr) {
    q.lighting = [lighting](double t) { return lighting->info_at(t); };
    q.lighting_change_at = [lighting](const glm::dvec3& p, double t) {
      return lighting->local_change_rate(p, t);
    };
    q.lighting_static = lighting->is_static();
    q.has_lamps = lighting->lamps() != nullptr;
    if (q.has_lamps) {
      q.lamp_positions = lighting->lamps()->positions();
      q.lamp_reach_m = lighting->lamps()->reach_m();
    }
  }
  q.ground_height = [&world](double x, double y) { return world.ground_height(x, y); };
  q.surface_height = [&world](double x, double y) { return world.surface_height(x, y); };
  q.road = world.road().empty() ? nullptr : &world.road();
  q.bounds_min = {world.min_xy().x, world.min_xy().y, world.min_surface()};
  q.bounds_max = {world.max_xy().x, world.max_xy().y, world.max_surface()};
  return q;
}

}  // namespace ambisim
