// `ambisim run SCENARIO.json --planner NAME [--set key=value ...] --out DIR
//  [--record-camera FILE.csv]`: one run; optionally the camera of every frame as a recording
//  (time,x,y,z,cut) that a "recorded" camera replays.
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <memory>

#include "apps/commands.h"
#include "policies/registry/registry.h"
#include "sim/run/reference_track.h"
#include "sim/run/run_output.h"
#include "sim/scenario/scenario.h"
#include "sim/scenario/scenario_motion.h"
#include "sim/world/world.h"

namespace ambisim::cli {
namespace {

// Runs without --planner use ambisim's own planner.
constexpr const char* kDefaultPlanner = "ambisim";

struct RunOptions {
  std::string scenario;
  std::string planner = kDefaultPlanner;
  std::vector<std::string> set;
  std::string preset;
  std::string out;
  std::string record_camera;
  bool force = false;
  bool quiet = false;
};

void run_run(const RunOptions& o) {
  const Overwrite ow = o.force ? Overwrite::allow : Overwrite::refuse;
  // Everything that can be refused is checked before the expensive part.
  const Scenario scenario = load_scenario(o.scenario);
  const PlannerParams params = planner_params_from_cli(o.planner, o.set, o.preset);
  auto planner = make_planner(o.planner, params);
  namespace fs = std::filesystem;
  std::error_code ec;
  const auto status = fs::status(o.out, ec);
  if (ec && ec != std::errc::no_such_file_or_directory && ec != std::errc::not_a_directory) {
    throw InputError(o.out, "", "cannot be used as the output directory: " + ec.message());
  }
  if (fs::exists(status) && !fs::is_directory(status)) {
    throw InputError(o.out, "", "exists and is not a directory");
  }
  if (fs::exists(status)) {
    check_output_path((fs::path(o.out) / "result.json").string(), ow);
    check_output_path((fs::path(o.out) / "frames.csv").string(), ow);
    check_output_path((fs::path(o.out) / "views.json").string(), ow);
  } else {
    // The directory is created at the end: its nearest existing ancestor must be a writable
    // directory now, not after the simulation.
    fs::path parent = fs::absolute(fs::path(o.out)).parent_path();
    while (!parent.empty() && !fs::exists(parent) && parent != parent.parent_path()) {
      parent = parent.parent_path();
    }
    if (!fs::is_directory(parent)) {
      throw InputError(o.out, "", "cannot be created: " + parent.string() + " is not a directory");
    }
    if (::access(parent.c_str(), W_OK) != 0) {
      throw InputError(o.out, "", "cannot be created: " + parent.string() + " is not writable");
    }
  }

  if (!o.record_camera.empty()) check_output_path(o.record_camera, ow);

  const World world(scenario.world);
  check_scenario_world(scenario, world);
  const auto reference = compute_reference_track(scenario, world);
  const RunResult result = simulate(scenario, world, *reference, *planner);
  write_run_output(o.out, scenario, {planner->name(), planner->params()}, result, ow);
  if (!o.record_camera.empty()) {
    write_text_atomically(o.record_camera, camera_csv(record_camera(scenario, world)), ow);
  }
  if (!o.quiet) {
    const Summary& s = result.summary;
    std::printf(
        "%s on %s: %lld frames; viewed: dE00 mean %.3f p95 %.3f, pops/min %.2f; uniform: dE00 "
        "mean %.3f p95 %.3f, pops/min %.2f; response median %.2f s (%lld events); coverage "
        "%.3f, faces used %lld, max live probes %lld (%.1f s)\n",
        planner->name().c_str(), scenario.name.c_str(), static_cast<long long>(s.frames),
        s.de2000_viewed.mean, s.de2000_viewed.p95, s.pops_viewed.per_min, s.de2000.mean,
        s.de2000.p95, s.pops.per_min, s.response.median_s,
        static_cast<long long>(s.response.events), s.coverage.mean,
        static_cast<long long>(s.faces.used), static_cast<long long>(s.probes.max_live),
        result.timing.total_s);
  }
}

}  // namespace

void add_run_command(CLI::App& app) {
  auto o = std::make_shared<RunOptions>();
  auto* cmd = app.add_subcommand("run", "simulate one scenario with one planner");
  cmd->add_option("scenario", o->scenario, "scenario JSON file")->required();
  cmd->add_option("--planner", o->planner, "planner name (see `ambisim planners`)");
  cmd->add_option("--set", o->set, "planner parameter key=value (repeatable)");
  cmd->add_option("--preset", o->preset,
                  "a named parameter set under --set, e.g. tuned (`ambisim planners` lists them)");
  cmd->add_option("--out", o->out, "output directory (result.json, frames.csv)")->required();
  cmd->add_option("--record-camera", o->record_camera,
                  "also write the camera of every frame as CSV (time,x,y,z,cut)");
  cmd->add_flag("--force", o->force, "overwrite an existing result");
  cmd->add_flag("--quiet", o->quiet, "print nothing on success");
  cmd->callback([o] { run_run(*o); });
}

void add_planners_command(CLI::App& app) {
  auto json = std::make_shared<bool>(false);
  auto* cmd = app.add_subcommand("planners", "list the planners and their parameters");
  cmd->add_flag("--json", *json, "machine-readable output");
  cmd->callback([json] {
    if (*json) {
      std::printf("%s\n", catalogue_json().dump(2).c_str());
    } else {
      std::printf("%s", format_catalogue().c_str());
    }
  });
}

}  // namespace ambisim::cli
