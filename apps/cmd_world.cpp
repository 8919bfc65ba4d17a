// `ambisim world SCENARIO.json --png FILE.png [--landmarks]`: a top-down colour map of the
// world; with --landmarks also the landmarks a scenario may name (landmark_ref.h), one a line.
#include <cstdio>
#include <memory>

#include "apps/commands.h"
#include "sim/scenario/scenario_file.h"
#include "sim/world/landmarks.h"
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
};

void run_world(const WorldOptions& o) {
  const Overwrite ow = o.force ? Overwrite::allow : Overwrite::refuse;
  check_output_path(o.png, ow);
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
  write_png(world_map_image(world, o.size_px), o.png, ow);
}

}  // namespace

void add_world_command(CLI::App& app) {
  auto o = std::make_shared<WorldOptions>();
  auto* cmd = app.add_subcommand("world", "generate the world and write a top-down map");
  cmd->add_option("scenario", o->scenario, "scenario JSON file (its \"world\" section is used)")
      ->required();
  cmd->add_option("--png", o->png, "output PNG")->required();
  cmd->add_option("--size", o->size_px, "largest image side in pixels")
      ->check(CLI::Range(16, 8192));
  cmd->add_flag("--force", o->force, "overwrite an existing output file");
  cmd->add_flag("--landmarks", o->landmarks, "print the world's landmarks");
  cmd->callback([o] { run_world(*o); });
}

}  // namespace ambisim::cli
