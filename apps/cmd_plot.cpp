// `ambisim plot DIR [--run ID] [--force]`: PNG charts of a sweep into DIR/charts/.
#include <cstdio>
#include <memory>

#include "apps/commands.h"
#include "viz/charts.h"

namespace ambisim::cli {
namespace {

struct PlotCliOptions {
  std::string dir;
  std::string run;
  bool force = false;
};

void run_plot_command(const PlotCliOptions& o) {
  PlotOptions opt;
  opt.run_id = o.run;
  opt.overwrite = o.force ? Overwrite::allow : Overwrite::refuse;
  const auto written = write_sweep_charts(o.dir, opt);
  for (const auto& f : written) std::printf("%s\n", f.c_str());
}

}  // namespace

void add_plot_command(CLI::App& app) {
  auto o = std::make_shared<PlotCliOptions>();
  auto* cmd = app.add_subcommand("plot", "PNG charts of a sweep directory into DIR/charts/");
  cmd->add_option("dir", o->dir, "sweep output directory (with summary.csv)")->required();
  cmd->add_option("--run", o->run, "run id for the time-series chart (default: first run)");
  cmd->add_flag("--force", o->force, "overwrite existing charts");
  cmd->callback([o] { run_plot_command(*o); });
}

}  // namespace ambisim::cli
