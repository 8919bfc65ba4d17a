#pragma once
// The views of a World that other parts may use: terrain queries for camera paths and
// receivers, and the game-engine knowledge a planner may use (never the lighting).
#include "sim/planner.h"
#include "sim/world/terrain_queries.h"
#include "sim/world/world.h"

namespace ambisim {

TerrainQueries terrain_queries(const World& world);
class LightingModel;

// `lighting` (may be null: no lighting queries) must outlive the queries.
WorldQueries planner_world_queries(const World& world, LightingModel* lighting = nullptr);

}  // namespace ambisim
