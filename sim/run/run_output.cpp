#include "sim/run/run_output.h"

#include <filesystem>

#include "sim/base/input_error.h"

namespace ambisim {
namespace {

nlohmann::ordered_json series_json(const RunResult& r) {
  // Column arrays keep the file compact and easy to plot.
  nlohmann::ordered_json s;
  auto column = [&](const char* name, auto get) {
    nlohmann::json a = nlohmann::json::array();
    for (const auto& f : r.frames) {
      const double v = static_cast<double>(get(f));
      a.push_back(std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr));
    }
    s[name] = std::move(a);
  };
  column("frame", [](const FrameRow& f) { return f.frame; });
  column("time", [](const FrameRow& f) { return f.time; });
  column("dt", [](const FrameRow& f) { return f.dt; });
  column("receivers", [](const FrameRow& f) { return f.receivers; });
  column("de2000_mean", [](const FrameRow& f) { return f.de2000_mean; });
  column("de2000_max", [](const FrameRow& f) { return f.de2000_max; });
  column("rel_mean", [](const FrameRow& f) { return f.rel_mean; });
  column("de2000_viewed_mean", [](const FrameRow& f) { return f.de2000_viewed_mean; });
  column("pops", [](const FrameRow& f) { return f.pops; });
  column("viewed_pops", [](const FrameRow& f) { return f.viewed_pops; });
  column("change_max", [](const FrameRow& f) { return f.change_max; });
  column("view_weight", [](const FrameRow& f) { return f.view_weight; });
  column("coverage", [](const FrameRow& f) { return f.coverage; });
  column("staleness_mean", [](const FrameRow& f) { return f.staleness_mean; });
  column("live_probes", [](const FrameRow& f) { return f.live_probes; });
  column("bytes", [](const FrameRow& f) { return f.bytes; });
  column("faces_granted", [](const FrameRow& f) { return f.faces_granted; });
  column("faces_used", [](const FrameRow& f) { return f.faces_used; });
  return s;
}

}  // namespace

nlohmann::ordered_json result_json(const Scenario& scenario, const RunIdentity& id,
                                   const RunResult& result) {
  nlohmann::ordered_json j;
  j["format"] = "ambisim-run";
  j["format_version"] = kResultFormatVersion;
  j["scenario"] = {{"name", scenario.name},
                   {"hash", hex64(scenario.hash())},
                   {"reference_hash", hex64(scenario.reference_hash())},
                   {"world_seed", scenario.world.seed},
                   {"receivers_seed", scenario.receivers.seed},
                   {"frames", result.summary.frames},
                   {"face_size", scenario.budget.face_size},
                   {"faces_per_frame", scenario.budget.faces_per_frame},
                   {"reference_face_size", scenario.reference.face_size},
                   {"reference_interval_s", scenario.reference.interval_s},
                   {"document", scenario.document}};
  j["planner"] = {{"name", id.planner}, {"params", id.planner_params}};
  if (!id.run.is_null()) j["run"] = id.run;
  j["metrics"] = metric_settings_to_json(scenario.metrics);
  j["exposure"] = result.exposure;
  j["summary"] = RunMetrics::to_json(result.summary);
  j["captures"] = {{"started", result.captures_started}, {"delivered", result.captures_delivered}};
  j["reference"] = {{"captures", result.reference_captures},
                    {"receiver_frames", result.reference_slots},
                    {"interpolated", result.reference_interpolated}};
  j["series"] = series_json(result);
  return j;
}

std::string views_json(const RunResult& result) {
  // Compact arrays: what `ambisim viz` needs to draw the run, nothing it could recompute.
  auto vec = [](const glm::dvec3& p) { return nlohmann::json::array({p.x, p.y, p.z}); };
  nlohmann::ordered_json j;
  j["format"] = "ambisim-views";
  j["format_version"] = kResultFormatVersion;
  j["exposure"] = result.exposure;
  nlohmann::json path = nlohmann::json::array();
  for (const auto& p : result.camera_path) path.push_back(vec(p));
  j["camera_path"] = std::move(path);
  nlohmann::json snaps = nlohmann::json::array();
  for (const auto& s : result.snapshots) {
    nlohmann::json o;
    o["frame"] = s.frame;
    o["time"] = s.time;
    o["camera"] = vec(s.camera);
    nlohmann::json nodes = nlohmann::json::array();
    for (const auto& n : s.nodes) {
      nlohmann::json sh = nlohmann::json::array();
      for (const auto& c : n.sh.c) sh.push_back({c.x, c.y, c.z});
      nodes.push_back({{"c", vec(n.centre)},
                       {"h", vec(n.half_extent)},
                       {"depth", n.depth},
                       {"data", n.has_data},
                       {"flight", n.in_flight},
                       {"age", n.age_s},
                       {"sh", std::move(sh)}});
    }
    o["nodes"] = std::move(nodes);
    nlohmann::json rec = nlohmann::json::array();
    for (const auto& p : s.receivers) rec.push_back(vec(p));
    o["receivers"] = std::move(rec);
    if (!s.light.empty()) {
      auto rgb = [](const Rgb& c) { return nlohmann::json::array({c.x, c.y, c.z}); };
      nlohmann::json light = nlohmann::json::array();
      for (const auto& l : s.light) {
        light.push_back({{"pu", rgb(l.planner_up)},
                         {"ru", rgb(l.reference_up)},
                         {"pv", rgb(l.planner_view)},
                         {"rv", rgb(l.reference_view)},
                         {"de", l.de2000_view},
                         {"pop", l.viewed_pop}});
      }
      o["light"] = std::move(light);
    }
    snaps.push_back(std::move(o));
  }
  j["snapshots"] = std::move(snaps);
  return j.dump() + "\n";
}

std::string frames_csv(const RunResult& result) {
  std::string out = frame_csv_header() + "\n";
  for (const auto& f : result.frames) out += frame_csv_row(f) + "\n";
  return out;
}

void write_run_output(const std::string& dir, const Scenario& scenario, const RunIdentity& id,
                      const RunResult& result, Overwrite overwrite) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir)) throw InputError(dir, "", "cannot create output directory");
  const std::string result_path = (fs::path(dir) / "result.json").string();
  const std::string frames_path = (fs::path(dir) / "frames.csv").string();
  // Check both before writing either, so a refusal leaves nothing half-written.
  check_output_path(result_path, overwrite);
  check_output_path(frames_path, overwrite);
  const std::string views_path = (fs::path(dir) / "views.json").string();
  check_output_path(views_path, overwrite);
  nlohmann::ordered_json j = result_json(scenario, id, result);
  j["timing"] = result.timing.to_json();
  write_text_atomically(frames_path, frames_csv(result), overwrite);
  write_text_atomically(views_path, views_json(result), overwrite);
  write_text_atomically(result_path, j.dump(1) + "\n", overwrite);
}

}  // namespace ambisim
