// `ambisim film RUN_DIR [RUN_DIR ...] --out FILE.mp4 [--from S --to S] [--size WxH] [--fps N]
//  [--force]`: the camera's view of runs of one scenario, one panel per run and one of the
// truth, as an MP4 and a contact sheet (FILE_contact.png beside it).
//
// What the film shows is what was scored: each run is re-run from its result.json (scenario
// document, planner and parameters; the simulator is deterministic) and filmed only when the
// re-run's summary equals the recorded one.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <set>

#include "apps/commands.h"
#include "policies/registry/registry.h"
#include "sim/base/input_error.h"
#include "sim/base/json_reader.h"
#include "sim/run/reference_track.h"
#include "sim/run/run_output.h"
#include "sim/scenario/scenario.h"
#include "sim/world/world.h"
#include "viz/film.h"

namespace ambisim::cli {
namespace {

namespace fs = std::filesystem;

struct FilmCliOptions {
  std::vector<std::string> run_dirs;
  std::string out;
  double from = 0.0;
  double to = -1.0;  // < 0: the run's end
  std::string size = "640x360";
  int fps = 30;
  bool force = false;
};

struct RecordedRun {
  std::string dir;
  std::string result_path;
  nlohmann::json result;
  Scenario scenario;
};

RecordedRun read_run(const std::string& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw InputError(dir, "", "is not a run directory");
  const std::string path = (fs::path(dir) / "result.json").string();
  if (!fs::is_regular_file(path, ec)) {
    throw InputError(path, "", "missing: " + dir + " is not a run directory");
  }
  nlohmann::json j = load_json_file(path);
  if (!j.is_object() || j.value("format", "") != "ambisim-run") {
    throw InputError(path, "/format", "not an ambisim run result");
  }
  if (j.value("format_version", 0) != kResultFormatVersion) {
    throw InputError(
        path, "/format_version",
        "written by another version (expected " + std::to_string(kResultFormatVersion) + ")");
  }
  for (const char* key : {"scenario", "planner", "summary"}) {
    if (!j.contains(key) || !j[key].is_object()) {
      throw InputError(path, std::string("/") + key, "missing");
    }
  }
  if (!j["scenario"].contains("document")) {
    throw InputError(path, "/scenario/document", "missing");
  }
  Scenario s = parse_scenario(j["scenario"]["document"], path);
  if (hex64(s.hash()) != j["scenario"].value("hash", "")) {
    // Recordings are read next to result.json here; a scenario whose files are elsewhere (or
    // changed since) cannot be re-run faithfully.
    throw InputError(path, "/scenario/hash",
                     "the scenario cannot be rebuilt as it was run (its hash differs)");
  }
  return {dir, path, std::move(j), std::move(s)};
}

std::pair<int, int> parse_size(const std::string& s) {
  int w = 0, h = 0;
  char x = 0, extra = 0;
  if (std::sscanf(s.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || x != 'x' || w < 16 || h < 16 ||
      w > 3840 || h > 2160 || w % 2 != 0 || h % 2 != 0) {
    throw InputError("--size", "", "must be WxH, even, 16..3840 x 16..2160, got " + s);
  }
  return {w, h};
}

std::string contact_sheet_path(const std::string& out) {
  fs::path p(out);
  return (p.parent_path() / (p.stem().string() + "_contact.png")).string();
}

void run_film(const FilmCliOptions& o) {
  const Overwrite ow = o.force ? Overwrite::allow : Overwrite::refuse;
  const auto [width, height] = parse_size(o.size);
  if (o.fps < 1 || o.fps > 240) {
    throw InputError("--fps", "", "must be 1..240, got " + std::to_string(o.fps));
  }
  // Everything that can be refused is checked before the expensive part.
  std::vector<RecordedRun> runs;
  for (const auto& d : o.run_dirs) runs.push_back(read_run(d));
  const std::string ref_hash = runs[0].result["scenario"].value("reference_hash", "");
  for (const auto& r : runs) {
    if (r.result["scenario"].value("reference_hash", "") != ref_hash) {
      throw InputError(r.result_path, "/scenario",
                       "a run of another scenario (" + r.scenario.name + ", reference " +
                           r.result["scenario"].value("reference_hash", "") + ", not " +
                           runs[0].scenario.name + ", reference " + ref_hash +
                           "): a film compares runs of one scenario and world");
    }
  }
  const double duration = runs[0].result["summary"].value("duration_s", 0.0);
  const double to = o.to < 0.0 ? duration : o.to;
  if (!(o.from >= 0.0) || !(to > o.from) || to > duration + 1e-6) {
    char buf[200];
    std::snprintf(buf, sizeof buf, "the time range %.3f..%.3f s is not inside the run (0..%.3f s)",
                  o.from, to, duration);
    throw InputError(runs[0].result_path, "/summary/duration_s", buf);
  }
  const std::string sheet = contact_sheet_path(o.out);
  check_output_path(o.out, ow);
  check_output_path(sheet, ow);

  const World world(runs[0].scenario.world);
  check_scenario_world(runs[0].scenario, world);
  const auto reference = compute_reference_track(runs[0].scenario, world);

  std::vector<FilmRun> film_runs;
  double exposure = 1.0, fov = 70.0;
  std::set<std::string> names;
  for (const auto& r : runs) {
    const std::string name = r.result["planner"].value("name", "");
    const nlohmann::json params = r.result["planner"].value("params", nlohmann::json::object());
    const PlannerParams pp =
        planner_params_from_json(name, params, r.result_path, "/planner/params");
    auto planner = make_planner(name, pp);
    FilmRun fr;
    fr.label =
        names.insert(name).second ? name : name + " [" + fs::path(r.dir).filename().string() + "]";
    SimulationOptions options;
    options.on_frame = [&](const FrameObservation& f) {
      if (f.time >= o.from - kFilmRingSeconds - 1e-9 && f.time <= to + 1e-9) {
        fr.frames.push_back(f);
      }
    };
    const RunResult result = simulate(r.scenario, world, *reference, *planner, options);
    const auto again = result_json(r.scenario, {planner->name(), planner->params()}, result);
    if (nlohmann::json::parse(again["summary"].dump()) != r.result["summary"]) {
      throw InputError(r.result_path, "/summary",
                       "the re-run does not reproduce this result (another version of ambisim "
                       "or planner?): not filmed");
    }
    exposure = result.exposure;
    if (!fr.frames.empty()) fov = fr.frames.front().view.fov_deg;
    film_runs.push_back(std::move(fr));
  }

  const std::vector<FilmFrame> frames = compose_film(film_runs, o.from, to, o.fps);
  FilmSettings settings;
  settings.panel_width = width;
  settings.panel_height = height;
  settings.fps = o.fps;
  settings.fov_deg = fov;
  settings.exposure = exposure;
  settings.light_time_s = o.from;
  for (const auto& f : frames) settings.camera_positions.push_back(f.camera);
  settings.overwrite = ow;
  write_film(world, settings, frames, o.out, sheet);
  std::printf("%s: %zu frames at %d fps (%d x %d), %zu panels; contact sheet %s\n", o.out.c_str(),
              frames.size(), o.fps, width * static_cast<int>(film_runs.size() + 1), height,
              film_runs.size() + 1, sheet.c_str());
}

}  // namespace

void add_film_command(CLI::App& app) {
  auto o = std::make_shared<FilmCliOptions>();
  auto* cmd = app.add_subcommand(
      "film", "an MP4 of the camera's view: each run's receivers beside the truth, pops ringed");
  cmd->add_option("run_dirs", o->run_dirs, "run directories (of one scenario)")->required();
  cmd->add_option("--out", o->out, "the MP4 to write (and FILE_contact.png beside it)")->required();
  cmd->add_option("--from", o->from, "start, simulated seconds (default 0)");
  cmd->add_option("--to", o->to, "end, simulated seconds (default: the run's end)");
  cmd->add_option("--size", o->size, "size of each panel, WxH (even; default 640x360)");
  cmd->add_option("--fps", o->fps, "film frames per second (default 30)");
  cmd->add_flag("--force", o->force, "overwrite an existing film");
  cmd->callback([o] { run_film(*o); });
}

}  // namespace ambisim::cli
