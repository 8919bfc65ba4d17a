// `ambisim viz RUN_DIR [--frames F1,F2,...] [--force]`: ParaView files and PNG snapshots of a
// run into RUN_DIR/views/.
#include <cstdio>
#include <memory>

#include "apps/commands.h"
#include "viz/views.h"

namespace ambisim::cli {
namespace {

struct VizCliOptions {
  std::string run_dir;
  std::vector<int> frames;
  bool force = false;
};

void run_viz_command(const VizCliOptions& o) {
  ViewsOptions opt;
  opt.frames = o.frames;
  opt.overwrite = o.force ? Overwrite::allow : Overwrite::refuse;
  const auto written = write_run_views(o.run_dir, opt);
  std::printf("%zu files written to %s/views\n", written.size(), o.run_dir.c_str());
}

}  // namespace

void add_viz_command(CLI::App& app) {
  auto o = std::make_shared<VizCliOptions>();
  auto* cmd =
      app.add_subcommand("viz", "ParaView files (.pvd/.vtp/.vtu/.vts) and PNG snapshots of a run");
  cmd->add_option("run_dir", o->run_dir, "run output directory (with views.json)")->required();
  cmd->add_option("--frames", o->frames, "frames to render as PNG (default: first, middle, last)")
      ->delimiter(',')
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("--force", o->force, "overwrite existing files");
  cmd->callback([o] { run_viz_command(*o); });
}

}  // namespace ambisim::cli
