#pragma once
// The validated description of a procedural world: everything World needs to regenerate it
// bit-identically. Defaults give the standard 4 km hilly world with a motorway.
#include <cstdint>
#include <memory>

#include <glm/vec2.hpp>

#include "sim/colour/rgb.h"
#include "sim/world/lighting_params.h"
#include "sim/world/terrain_level.h"

namespace ambisim {

class ObjectReader;

struct TerrainParams {
  double amplitude_m = 220.0;     // height range of the hills (m), >= 0
  double wavelength_m = 1400.0;   // largest feature size (m), > 0
  double roughness = 0.5;         // fBm persistence, 0..0.9
  double ridge_weight = 0.45;     // share of ridged noise (steep crests), 0..1
  double cliff_height_m = 35.0;   // height of escarpments (cliff bands), >= 0
  double water_level_m = 30.0;    // lakes fill terrain below this height
  double snow_line_m = 205.0;     // snow above this height
  double forest_fraction = 0.35;  // target share of forest on suitable ground, 0..1
  double field_fraction = 0.35;   // share of flat lowland parcels that are fields, 0..1
  double canopy_min_m = 15.0;     // canopy height above ground, range [min, max]
  double canopy_max_m = 25.0;
};

struct RoadParams {
  bool enabled = true;
  double width_m = 24.0;          // asphalt width (both carriageways)
  double shoulder_m = 6.0;        // graded flat verge on each side
  double clearance_m = 25.0;      // no canopy closer than this to the asphalt edge
  double smoothing_m = 400.0;     // window of the road-profile smoothing (grading)
  double meander_m = 600.0;       // lateral amplitude of the winding centre line
  double cutting_slope_deg = 72;  // rock walls of cuttings
  double embankment_slope_deg = 33;
};

struct WorldParams {
  std::uint64_t seed = 1;
  glm::dvec2 size_m{4096.0, 4096.0};  // extent east x north; multiples of cell_m
  double cell_m = 2.0;                // grid cell edge
  glm::dvec2 origin{0.0, 0.0};        // world-frame position of the grid's south-west corner
  TerrainParams terrain;
  RoadParams road;
  SunParams sun;
  SkyParams sky;
  CloudParams clouds;
  LampParams lamps;
  FogParams fog;
  // An imported terrain ("level", terrain_level.h) instead of the generated one: it sets
  // size_m and cell_m, and there is no road. Shared: the decoded maps are read once and
  // copied with the params by pointer; null for the procedural world.
  std::shared_ptr<const TerrainLevel> level;

  LightingParams lighting() const { return {sun, sky, clouds, lamps, fog}; }
};

// Reads a "world" object. Every key is optional (defaults above); unknown keys and values out
// of range throw InputError naming the JSON path.
WorldParams parse_world_params(ObjectReader& r);

}  // namespace ambisim
