// `ambisim bench-chart BENCH.json --out PNG [--force]`: lookup and per-frame planner cost
// against live probes, from bench/bench_planners' Google Benchmark JSON.
#include <cstdio>
#include <memory>

#include "apps/commands.h"
#include "viz/bench_chart.h"

namespace ambisim::cli {
namespace {

struct BenchChartOptions {
  std::string input;
  std::string out;
  bool force = false;
};

}  // namespace

void add_bench_chart_command(CLI::App& app) {
  auto o = std::make_shared<BenchChartOptions>();
  auto* cmd = app.add_subcommand(
      "bench-chart", "PNG of planner lookup and frame cost against live probes (bench_planners)");
  cmd->add_option("bench_json", o->input, "bench_planners --benchmark_out JSON file")->required();
  cmd->add_option("--out", o->out, "PNG to write")->required();
  cmd->add_flag("--force", o->force, "overwrite an existing PNG");
  cmd->callback([o] {
    write_planner_bench_chart(o->input, o->out, o->force ? Overwrite::allow : Overwrite::refuse);
    std::printf("%s\n", o->out.c_str());
  });
}

}  // namespace ambisim::cli
