#include "sim/world/world_params.h"

#include <cmath>
#include <memory>
#include <string>

#include "sim/base/json_reader.h"

namespace ambisim {
namespace {

constexpr double kMaxCells = 67108864.0;  // 2^26

TerrainParams parse_terrain(ObjectReader& r) {
  TerrainParams t;
  t.amplitude_m = r.number("amplitude_m", t.amplitude_m, Range::closed(0.0, 5000.0));
  t.wavelength_m = r.number("wavelength_m", t.wavelength_m, Range::closed(10.0, 1e6));
  t.roughness = r.number("roughness", t.roughness, Range::closed(0.0, 0.9));
  t.ridge_weight = r.number("ridge_weight", t.ridge_weight, Range::unit());
  t.cliff_height_m = r.number("cliff_height_m", t.cliff_height_m, Range::closed(0.0, 1000.0));
  t.water_level_m = r.number("water_level_m", t.water_level_m);
  t.snow_line_m = r.number("snow_line_m", t.snow_line_m);
  t.forest_fraction = r.number("forest_fraction", t.forest_fraction, Range::unit());
  t.field_fraction = r.number("field_fraction", t.field_fraction, Range::unit());
  t.canopy_min_m = r.number("canopy_min_m", t.canopy_min_m, Range::closed(0.0, 100.0));
  t.canopy_max_m = r.number("canopy_max_m", t.canopy_max_m, Range::closed(0.0, 100.0));
  if (t.canopy_max_m < t.canopy_min_m) r.fail("canopy_max_m", "must be >= canopy_min_m");
  r.finish();
  return t;
}

RoadParams parse_road(ObjectReader& r) {
  RoadParams p;
  p.enabled = r.boolean("enabled", p.enabled);
  p.width_m = r.number("width_m", p.width_m, Range::closed(2.0, 200.0));
  p.shoulder_m = r.number("shoulder_m", p.shoulder_m, Range::closed(0.0, 100.0));
  p.clearance_m = r.number("clearance_m", p.clearance_m, Range::closed(0.0, 500.0));
  p.smoothing_m = r.number("smoothing_m", p.smoothing_m, Range::closed(0.0, 5000.0));
  p.meander_m = r.number("meander_m", p.meander_m, Range::closed(0.0, 1e5));
  p.cutting_slope_deg = r.number("cutting_slope_deg", p.cutting_slope_deg, {1.0, 89.0});
  p.embankment_slope_deg = r.number("embankment_slope_deg", p.embankment_slope_deg, {1.0, 89.0});
  r.finish();
  return p;
}

}  // namespace

WorldParams parse_world_params(ObjectReader& r) {
  WorldParams w;
  w.seed = r.seed("seed", w.seed);
  if (auto o = r.optional_object("level")) {
    // The level's images fix the grid and carry the terrain: the generator's keys would be
    // silently ignored, so they are refused.
    for (const char* key : {"size_m", "cell_m", "terrain"}) {
      if (r.has(key)) {
        r.fail(key, std::string("not with an imported level (/world/level sets the ") +
                        (std::string(key) == "terrain" ? "terrain)" : "grid: use its cell_m)"));
      }
    }
    auto level = std::make_shared<TerrainLevel>(parse_terrain_level(*o));
    w.cell_m = level->cell_m;
    w.size_m = {level->nx * level->cell_m, level->ny * level->cell_m};
    w.level = std::move(level);
  }
  if (!w.level) {
    w.size_m = r.vec2("size_m", w.size_m, Range::closed(16.0, 65536.0));
    w.cell_m = r.number("cell_m", w.cell_m, Range::closed(0.05, 64.0));
  }
  w.origin = r.vec2("origin", w.origin, Range::closed(-1e9, 1e9));
  for (int k = 0; k < 2; ++k) {
    const double n = w.size_m[k] / w.cell_m;
    if (std::abs(n - std::round(n)) > 1e-9 * n) r.fail("size_m", "must be a multiple of cell_m");
  }
  if (w.size_m.x / w.cell_m > 16384 || w.size_m.y / w.cell_m > 16384) {
    r.fail("cell_m", "too small for size_m: at most 16384 cells per side");
  }
  // About 40 bytes per cell (heights, shadow map, biome, albedo, radiance, pyramid): 2^26
  // cells (8192 x 8192) is some 3 GB.
  if (w.size_m.x / w.cell_m * (w.size_m.y / w.cell_m) > kMaxCells) {
    r.fail("cell_m", "too small for size_m: at most 67108864 (8192 x 8192) cells in all");
  }
  if (auto o = r.optional_object("terrain")) w.terrain = parse_terrain(*o);
  if (auto o = r.optional_object("road")) w.road = parse_road(*o);
  if (w.level) {
    if (w.road.enabled && r.has("road")) {
      r.fail("road", "an imported level (/world/level) has no road: leave out /world/road");
    }
    w.road.enabled = false;
  }
  // The sky first: which sun keys apply depends on its model.
  if (auto o = r.optional_object("sky")) w.sky = parse_sky(*o);
  if (auto o = r.optional_object("sun")) w.sun = parse_sun(*o, w.sky.model);
  if (auto o = r.optional_object("clouds")) w.clouds = parse_clouds(*o, w.seed);
  if (auto o = r.optional_object("lamps")) w.lamps = parse_lamps(*o);
  if (auto o = r.optional_object("fog")) w.fog = parse_fog(*o);
  if (w.lamps.enabled && !w.road.enabled) {
    r.fail("lamps", w.level ? "street lamps stand along the road: an imported level "
                              "(/world/level) has none"
                            : "street lamps stand along the road: /world/road/enabled is false");
  }
  r.finish();
  return w;
}

}  // namespace ambisim
