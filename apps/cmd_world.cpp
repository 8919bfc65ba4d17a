// `ambisim world SCENARIO.json --png FILE.png [--landmarks]`: a top-down colour map of the
// world; with --landmarks also the landmarks a scenario may name (landmark_ref.h), one a line.
// `--export-level DIR [--region X0,Y0,X1,Y1] [--stride N]`: a piece of the world as the
// heightmap, albedo, canopy and water PNGs of an importable level (level_export.h) and the
// world section's "level" object for them in DIR/level.json.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <vector>

#include "apps/commands.h"
#include "sim/base/input_error.h"
#include "sim/base/output_file.h"
#include "sim/base/png_codec.h"
#include "sim/scenario/scenario_file.h"
#include "sim/world/landmarks.h"
#include "sim/world/level_export.h"
#include "sim/world/world.h"
#include "sim/world/world_map.h"
#include "viz/png_writer.h"

namespace ambisim::cli {
namespace {

struct WorldOptions {
  std::string scenario;
  std::string png;
  int size_px = 1024;
  bool force = false;
  bool landmarks = false;
  std::string level_dir;
  std::vector<double> region;  // X0,Y0,X1,Y1; empty: the whole grid
  int stride = 1;
};

const char* const kLevelFiles[] = {"height.png", "albedo.png", "canopy.png", "water.png",
                                   "level.json"};

void export_level_files(const World& world, const WorldOptions& o, Overwrite ow) {
  glm::dvec2 lo = world.min_xy(), hi = world.max_xy();
  if (!o.region.empty()) {
    lo = {o.region[0], o.region[1]};
    hi = {o.region[2], o.region[3]};
  }
  ExportedLevel level;
  try {
    level = export_level(world, lo, hi, o.stride);
  } catch (const std::invalid_argument& e) {
    throw InputError(o.scenario, "", std::string("--region/--stride: ") + e.what());
  }
  const std::string files[4] = {encode_png(level.heightmap), encode_png(level.albedo),
                                encode_png(level.canopy), encode_png(level.water)};
  const std::string dir = std::filesystem::path(o.level_dir).filename().string();
  nlohmann::json snippet = {{"level", level.level_object(dir)}};
  if (level.origin != glm::dvec2(0.0)) snippet["origin"] = {level.origin.x, level.origin.y};
  const std::string base = o.level_dir + "/";
  for (int k = 0; k < 4; ++k) write_text_atomically(base + kLevelFiles[k], files[k], ow);
  write_text_atomically(base + kLevelFiles[4], snippet.dump(2) + "\n", ow);
  std::printf(
      "level %d x %d cells of %.2f m in %s; its world section (paths relative to the "
      "directory holding %s):\n%s\n",
      level.heightmap.width, level.heightmap.height, level.cell_m, o.level_dir.c_str(), dir.c_str(),
      snippet.dump().c_str());
}

void run_world(const WorldOptions& o) {
  const Overwrite ow = o.force ? Overwrite::allow : Overwrite::refuse;
  if (o.png.empty() && o.level_dir.empty()) {
    throw InputError("", "", "world: give --png FILE, --export-level DIR or both");
  }
  if (o.level_dir.empty() && (!o.region.empty() || o.stride != 1)) {
    throw InputError("", "", "world: --region and --stride need --export-level DIR");
  }
  if (!o.png.empty()) check_output_path(o.png, ow);
  if (!o.level_dir.empty()) {
    std::error_code ec;
    if (!std::filesystem::is_directory(o.level_dir, ec)) {
      throw InputError(o.level_dir, "", "--export-level: not a directory (create it first)");
    }
    for (const char* f : kLevelFiles) check_output_path(o.level_dir + "/" + f, ow);
  }
  const World world(load_world_params(o.scenario));
  std::printf("world %.0f x %.0f m, %d x %d cells of %.2f m, hash %016llx\n",
              world.max_xy().x - world.min_xy().x, world.max_xy().y - world.min_xy().y, world.nx(),
              world.ny(), world.cell_m(), static_cast<unsigned long long>(world.content_hash()));
  if (o.landmarks) {
    for (const auto& name : landmark_names()) {
      const auto f = landmark_frame(world.landmarks(), name);
      if (!f) {
        std::printf("landmark %s: none in this world\n", name.c_str());
        continue;
      }
      std::printf("landmark %s: (%.1f, %.1f, %.1f), along (%.3f, %.3f)\n", name.c_str(),
                  f->origin.x, f->origin.y, f->origin.z, f->along.x, f->along.y);
    }
  }
  if (!o.level_dir.empty()) export_level_files(world, o, ow);
  if (!o.png.empty()) write_png(world_map_image(world, o.size_px), o.png, ow);
}

}  // namespace

void add_world_command(CLI::App& app) {
  auto o = std::make_shared<WorldOptions>();
  auto* cmd = app.add_subcommand(
      "world", "generate the world; write a top-down map or export it as a level");
  cmd->add_option("scenario", o->scenario, "scenario JSON file (its \"world\" section is used)")
      ->required();
  cmd->add_option("--png", o->png, "output PNG (a top-down map)");
  cmd->add_option("--export-level", o->level_dir,
                  "write the world as an importable level into this existing directory");
  cmd->add_option("--region", o->region, "exported region X0,Y0,X1,Y1 in world metres")
      ->expected(4)
      ->delimiter(',');
  cmd->add_option("--stride", o->stride, "exported cell = this many world cells a side")
      ->check(CLI::Range(1, 64));
  cmd->add_option("--size", o->size_px, "largest image side in pixels")
      ->check(CLI::Range(16, 8192));
  cmd->add_flag("--force", o->force, "overwrite an existing output file");
  cmd->add_flag("--landmarks", o->landmarks, "print the world's landmarks");
  cmd->callback([o] { run_world(*o); });
}

}  // namespace ambisim::cli
