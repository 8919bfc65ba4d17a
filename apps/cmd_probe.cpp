// `ambisim probe SCENARIO.json --at X,Y,Z`: one capture, its SH coefficients and irradiance.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <sstream>

#include <nlohmann/json.hpp>

#include "apps/commands.h"
#include "sim/base/input_error.h"
#include "sim/colour/tone_map.h"
#include "sim/render/capture.h"
#include "sim/render/cube_cross.h"
#include "sim/scenario/scenario_file.h"
#include "sim/sh/irradiance_reference.h"
#include "sim/sh/sh_projection.h"
#include "viz/png_writer.h"

namespace ambisim::cli {
namespace {

struct ProbeOptions {
  std::string scenario;
  std::vector<double> at;
  int size = 16;
  bool json = false;
  bool force = false;
  bool above_ground = false;
  std::string cube_png;
};

const std::array<glm::dvec3, 6> kAxes = {glm::dvec3{1, 0, 0}, glm::dvec3{-1, 0, 0},
                                         glm::dvec3{0, 1, 0}, glm::dvec3{0, -1, 0},
                                         glm::dvec3{0, 0, 1}, glm::dvec3{0, 0, -1}};
const std::array<const char*, 6> kAxisNames = {"+x", "-x", "+y", "-y", "+z", "-z"};

nlohmann::json rgb_json(const Rgb& c) { return {c.x, c.y, c.z}; }

void run_probe(const ProbeOptions& o) {
  if (o.at.size() != 3) throw InputError("--at", "", "expects X,Y,Z");
  for (double x : o.at) {
    // The world's origin may lie up to 1e9 m away; beyond 1e10 m a position is a mistake.
    if (!std::isfinite(x) || std::abs(x) > 1e10) {
      throw InputError("--at", "", "coordinates must be finite and within +-1e10 m");
    }
  }
  if (!o.cube_png.empty()) {
    check_output_path(o.cube_png, o.force ? Overwrite::allow : Overwrite::refuse);
  }
  const World world(load_world_params(o.scenario));
  const glm::dvec3 p(o.at[0], o.at[1],
                     o.at[2] + (o.above_ground ? world.ground_height(o.at[0], o.at[1]) : 0.0));
  const CubeMap cube = capture(world, p, o.size);
  const Sh9Rgb sh = projector_for(o.size).project(cube);

  nlohmann::json out;
  out["scenario"] = o.scenario;
  out["at"] = {p.x, p.y, p.z};
  out["capture_origin"] = {capture_origin(world, p).x, capture_origin(world, p).y,
                           capture_origin(world, p).z};
  out["face_size"] = o.size;
  out["ground_height"] = world.ground_height(p.x, p.y);
  out["biome"] = std::string(biome_name(world.biome_at(p.x, p.y)));
  out["sh9"] = nlohmann::json::array();
  for (const auto& c : sh.c) out["sh9"].push_back(rgb_json(c));
  for (int a = 0; a < 6; ++a) {
    out["irradiance_sh"][kAxisNames[a]] = rgb_json(sh_irradiance(sh, kAxes[a]));
    out["irradiance_exact"][kAxisNames[a]] = rgb_json(exact_irradiance(cube, kAxes[a]));
  }
  if (o.json) {
    std::cout << out.dump(2) << "\n";
  } else {
    const std::string biome(biome_name(world.biome_at(p.x, p.y)));
    std::printf("probe at (%.2f, %.2f, %.2f), biome %s, %dx%d per face\n", p.x, p.y, p.z,
                biome.c_str(), o.size, o.size);
    static const char* kNames[9] = {"00", "1-1", "10", "11", "2-2", "2-1", "20", "21", "22"};
    for (int k = 0; k < kShCount; ++k) {
      std::printf("  L%-4s %10.5f %10.5f %10.5f\n", kNames[k], sh.c[k].x, sh.c[k].y, sh.c[k].z);
    }
    std::printf("irradiance (SH9 | exact integral):\n");
    for (int a = 0; a < 6; ++a) {
      const Rgb e = sh_irradiance(sh, kAxes[a]);
      const Rgb x = exact_irradiance(cube, kAxes[a]);
      std::printf("  n=%s %9.4f %9.4f %9.4f | %9.4f %9.4f %9.4f\n", kAxisNames[a], e.x, e.y, e.z,
                  x.x, x.y, x.z);
    }
  }
  if (!o.cube_png.empty()) {
    // Exposure from the capture itself (Reinhard key 0.18): a view, not a metric.
    const double exposure = exposure_for_key(log_average_luminance(cube.texel));
    const int scale = std::max(1, 256 / o.size);
    write_png(cube_cross_image(cube, exposure, scale), o.cube_png,
              o.force ? Overwrite::allow : Overwrite::refuse);
  }
}

}  // namespace

void add_probe_command(CLI::App& app) {
  auto o = std::make_shared<ProbeOptions>();
  auto* cmd = app.add_subcommand("probe", "capture one probe and print its SH9 and irradiance");
  cmd->add_option("scenario", o->scenario, "scenario JSON file (its \"world\" section is used)")
      ->required();
  cmd->add_option("--at", o->at, "capture position X,Y,Z in metres")->required()->delimiter(',');
  cmd->add_option("--size", o->size, "cube face size in texels")->check(CLI::Range(1, 512));
  cmd->add_flag("--above-ground", o->above_ground, "Z is a height above the ground");
  cmd->add_flag("--json", o->json, "print JSON instead of a table");
  cmd->add_option("--cube", o->cube_png, "write the tone-mapped cube cross to this PNG");
  cmd->add_flag("--force", o->force, "overwrite existing output files");
  cmd->callback([o] { run_probe(*o); });
}

}  // namespace ambisim::cli
