#include "sim/run/sweep.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <future>
#include <map>
#include <mutex>
#include <set>
#include <thread>

#include "sim/base/hash.h"
#include "sim/base/input_error.h"
#include "sim/base/json_reader.h"
#include "sim/metrics/metrics.h"
#include "sim/run/reference_track.h"
#include "sim/run/run_output.h"
#include "sim/run/simulator.h"
#include "sim/world/world.h"

namespace ambisim {
namespace fs = std::filesystem;
namespace {

constexpr const char* kComponentRule =
    "must be 1..100 characters without '/' or '\\', and not \".\" or \"..\"";

// Scenario names and planner labels become directory names under runs/.
bool safe_path_component(const std::string& s) {
  return !s.empty() && s.size() <= 100 && s != "." && s != ".." &&
         s.find_first_of("/\\") == std::string::npos && s.find('\0') == std::string::npos;
}

std::string number_text(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", x);
  return buf;
}

// Multiplies every camera speed of a scenario document.
void scale_camera_speed(nlohmann::json& doc, double scale) {
  if (scale == 1.0 || !doc.contains("camera")) return;
  nlohmann::json& cam = doc["camera"];
  if (cam.contains("speed_mps") && cam["speed_mps"].is_number()) {
    cam["speed_mps"] = cam["speed_mps"].get<double>() * scale;
  }
  if (cam.contains("speed_profile") && cam["speed_profile"].is_array()) {
    for (auto& bp : cam["speed_profile"]) {
      if (bp.contains("speed_mps") && bp["speed_mps"].is_number()) {
        bp["speed_mps"] = bp["speed_mps"].get<double>() * scale;
      }
    }
  }
}

std::string csv_escape(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

// Flattens an (ordered) JSON object into dotted keys and CSV texts, in document order.
void flatten(const nlohmann::ordered_json& j, const std::string& prefix,
             std::vector<std::pair<std::string, std::string>>& out) {
  for (auto it = j.begin(); it != j.end(); ++it) {
    const std::string key = prefix.empty() ? it.key() : prefix + "." + it.key();
    const auto& v = it.value();
    if (v.is_object()) {
      flatten(v, key, out);
    } else if (v.is_null()) {
      out.emplace_back(key, "nan");
    } else if (v.is_number_integer()) {
      out.emplace_back(key, std::to_string(v.get<std::int64_t>()));
    } else if (v.is_number()) {
      out.emplace_back(key, format_number(v.get<double>()));
    } else if (v.is_string()) {
      out.emplace_back(key, csv_escape(v.get<std::string>()));
    } else {
      out.emplace_back(key, csv_escape(v.dump()));
    }
  }
}

std::uint64_t run_hash_of(const Scenario& sc, const SweepPlanner& p) {
  ContentHasher h;
  h.add_value(static_cast<std::uint64_t>(kResultsModelVersion));
  const std::uint64_t sh = sc.hash();
  h.add_value(sh);
  h.add_bytes(p.name.data(), p.name.size());
  const std::string params = p.params.dump();
  h.add_bytes(params.data(), params.size());
  return h.value();
}

nlohmann::json run_json(const RunSpec& r) {
  return {{"id", r.id},
          {"index", r.index},
          {"hash", hex64(r.run_hash)},
          {"label", r.planner.label},
          {"faces_per_frame", r.budget},
          {"speed_scale", r.speed_scale},
          {"fps", r.fps},
          {"seed", r.seed}};
}

std::optional<nlohmann::ordered_json> read_result(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  try {
    return nlohmann::ordered_json::parse(in);
  } catch (const nlohmann::json::exception&) {
    return std::nullopt;
  }
}

}  // namespace

SweepSpec parse_sweep(const nlohmann::json& doc, const std::string& path) {
  ObjectReader r(doc, path, "");
  SweepSpec s;
  s.file = path;
  s.name = r.string("name", fs::path(path).stem().string());
  const fs::path base = fs::path(path).parent_path();
  const nlohmann::json* scen = r.raw("scenarios");
  if (scen == nullptr) r.fail("scenarios", "required list of scenario files is missing");
  if (!scen->is_array() || scen->empty()) r.fail("scenarios", "must be a non-empty array of paths");
  for (std::size_t i = 0; i < scen->size(); ++i) {
    const auto& e = (*scen)[i];
    if (!e.is_string()) {
      throw InputError(path, "/scenarios/" + std::to_string(i), "must be a file path string");
    }
    const fs::path p = base / e.get<std::string>();
    std::error_code ec;  // e.g. a name too long for the file system: not a crash
    if (!fs::is_regular_file(p, ec)) {
      throw InputError(path, "/scenarios/" + std::to_string(i),
                       "no such file: " + p.string() + (ec ? " (" + ec.message() + ")" : ""));
    }
    s.scenarios.push_back(p.lexically_normal().string());
  }
  const nlohmann::json* planners = r.raw("planners");
  if (planners == nullptr) r.fail("planners", "required list of planners is missing");
  if (!planners->is_array() || planners->empty()) r.fail("planners", "must be a non-empty array");
  std::set<std::string> labels;
  for (std::size_t i = 0; i < planners->size(); ++i) {
    const std::string at = "/planners/" + std::to_string(i);
    SweepPlanner p;
    const auto& e = (*planners)[i];
    if (e.is_string()) {
      p.name = e.get<std::string>();
      p.params = nlohmann::json::object();
    } else {
      ObjectReader pr(e, path, at);
      p.name = pr.string("name");
      p.label = pr.string("label", "");
      // The label names the run directories: it must be one path component.
      if (!p.label.empty() && !safe_path_component(p.label)) {
        pr.fail("label", kComponentRule);
      }
      p.preset = pr.string("preset", "");
      p.preset_pointer = at + "/preset";
      const nlohmann::json* params = pr.raw("params");
      p.params = params ? *params : nlohmann::json::object();
      if (!p.params.is_object()) throw InputError(path, at + "/params", "must be an object");
      pr.finish();
    }
    if (p.label.empty()) p.label = p.preset.empty() ? p.name : p.name + "_" + p.preset;
    p.params_pointer = at + "/params";
    if (!labels.insert(p.label).second) {
      throw InputError(path, at, "duplicate planner label \"" + p.label + "\" (add \"label\")");
    }
    s.planners.push_back(std::move(p));
  }
  if (r.has("budgets")) s.budgets = r.numbers("budgets", Range::closed(0.0, 96.0));
  if (r.has("speed_scales")) s.speed_scales = r.numbers("speed_scales", Range::closed(0.0, 100.0));
  if (r.has("fps")) s.fps = r.numbers("fps", {0.0, 10000.0, true, false});
  if (r.has("seeds")) {
    for (double x : r.numbers("seeds", Range::closed(0.0, 9.0e15))) {
      if (x != std::floor(x)) r.fail("seeds", "seeds must be whole numbers");
      s.seeds.push_back(static_cast<std::uint64_t>(x));
    }
  }
  if (r.has("duration_s")) s.duration_s = r.number("duration_s", {0.0, 86400.0, true, false});
  if (const nlohmann::json* o = r.raw("overrides")) {
    if (!o->is_object()) r.fail("overrides", "must be an object of JSON pointer -> value");
    s.overrides = *o;
  }
  for (const char* k : {"budgets", "speed_scales", "fps", "seeds"}) {
    if (r.has(k) && doc[k].empty()) r.fail(k, "must not be empty");
  }
  // The scenario parser limits every variant to 1e6 frames; say so here, where both are set.
  if (s.duration_s && !s.fps.empty()) {
    const double top_fps = *std::max_element(s.fps.begin(), s.fps.end());
    const double frames = std::ceil(*s.duration_s * top_fps);
    if (frames > 1e6) {
      r.fail("duration_s", "with fps " + format_number(top_fps) + " gives " +
                               std::to_string(static_cast<long long>(frames)) +
                               " frames; at most 1000000");
    }
  }
  r.finish();
  return s;
}

SweepSpec load_sweep(const std::string& path) { return parse_sweep(load_json_file(path), path); }

void apply_seed(nlohmann::json& doc, std::uint64_t seed, const std::string& file) {
  const auto read = [&](const char* section) -> std::uint64_t {
    if (!doc.contains(section) || !doc[section].is_object()) return 1;
    const auto& sec = doc[section];
    if (!sec.contains("seed") || !sec["seed"].is_number_integer() ||
        sec["seed"].get<double>() < 0) {
      return 1;  // absent: the parser's default (an invalid one is reported by the parser)
    }
    return sec["seed"].get<std::uint64_t>();
  };
  const std::uint64_t world = read("world");
  const std::uint64_t receivers = read("receivers");
  set_json_path(doc, "/world/seed", seed, file);
  // 53 bits: the seed stays an exact JSON number.
  const std::uint64_t derived =
      seed == world ? receivers : splitmix64(hash_combine(receivers, seed)) >> 11;
  set_json_path(doc, "/receivers/seed", derived, file);
}

std::vector<RunSpec> expand_sweep(const SweepSpec& spec) {
  std::vector<RunSpec> runs;
  const std::vector<double> fps = spec.fps.empty() ? std::vector<double>{0.0} : spec.fps;
  const std::vector<std::uint64_t> seeds =
      spec.seeds.empty() ? std::vector<std::uint64_t>{0} : spec.seeds;
  for (const auto& file : spec.scenarios) {
    const nlohmann::json base = load_json_file(file);
    for (double f : fps) {
      for (double v : spec.speed_scales) {
        for (std::uint64_t seed : seeds) {
          nlohmann::json doc = base;
          for (const auto& [pointer, value] : spec.overrides.items()) {
            set_json_path(doc, pointer, value, spec.file);
          }
          if (spec.duration_s) set_json_path(doc, "/frames/duration_s", *spec.duration_s, file);
          if (f > 0.0) {
            if (doc.contains("frames") && doc["frames"].is_object())
              doc["frames"].erase("segments");
            set_json_path(doc, "/frames/fps", f, file);
          }
          if (seed != 0) apply_seed(doc, seed, file);
          scale_camera_speed(doc, v);
          for (double b : spec.budgets) {
            set_json_path(doc, "/budget/faces_per_frame", b, file);
            const Scenario variant = parse_scenario(doc, file);
            if (v != 1.0 && variant.camera.type == CameraPathRecord::Type::recorded) {
              throw InputError(
                  spec.file, "/speed_scales",
                  variant.name + " has a recorded camera: its speed cannot be scaled (only 1)");
            }
            if (!safe_path_component(variant.name)) {
              throw InputError(file, "/name",
                               std::string("names the run directories: ") + kComponentRule);
            }
            for (const auto& p : spec.planners) {
              RunSpec r;
              r.index = runs.size();
              r.scenario = variant;
              r.planner = p;
              r.budget = b;
              r.speed_scale = v;
              r.fps = f;
              r.seed = seed;
              r.id = variant.name + "__" + p.label + "__b" + number_text(b) + "__v" +
                     number_text(v) + (f > 0.0 ? "__f" + number_text(f) : std::string()) +
                     (seed != 0 ? "__s" + std::to_string(seed) : std::string());
              r.run_hash = run_hash_of(variant, p);
              runs.push_back(std::move(r));
            }
          }
        }
      }
    }
  }
  std::set<std::string> ids;
  for (const auto& r : runs) {
    if (!ids.insert(r.id).second) {
      throw InputError(
          spec.file, "",
          "two runs would share the id " + r.id + " (same scenario name listed twice?)");
    }
  }
  return runs;
}

SweepReport run_sweep(const SweepSpec& spec, const std::string& out_dir,
                      const PlannerFactory& factory, const SweepOptions& options) {
  const std::vector<RunSpec> all = expand_sweep(spec);
  // Validate every planner before any work, so a typo fails in a second, not an hour in.
  for (const auto& p : spec.planners) factory(p);

  std::vector<const RunSpec*> mine;
  for (const auto& r : all) {
    if (static_cast<int>(r.index % static_cast<std::size_t>(options.shard_count)) ==
        options.shard_index) {
      mine.push_back(&r);
    }
  }
  const fs::path runs_dir = fs::path(out_dir) / "runs";

  SweepReport report;
  report.total = mine.size();
  std::vector<const RunSpec*> todo;
  for (const RunSpec* r : mine) {
    const fs::path result = runs_dir / r->id / "result.json";
    if (fs::exists(result)) {
      if (options.resume) {
        const auto j = read_result(result);
        if (j && j->contains("run") && (*j)["run"].value("hash", "") == hex64(r->run_hash)) {
          ++report.skipped;
          continue;
        }
      } else if (!options.force) {
        throw InputError(result.string(), "",
                         "already exists (use --resume to keep finished runs or --force)");
      }
    }
    todo.push_back(r);
  }

  // Shared inputs: one World per world description, one reference per scenario variant.
  // The worlds are built now, one after the other, so that every run to do is checked against
  // its world (the road's length) before anything is written; after this the map is only read.
  auto world_key = [](const Scenario& sc) {
    std::string key = sc.document.value("world", nlohmann::json::object()).dump();
    // An imported level: the same document may name files whose bytes differ.
    if (sc.world.level) key += "#" + hex64(sc.world.level->content_hash);
    return key;
  };
  std::map<std::string, std::shared_ptr<const World>> worlds;
  for (const RunSpec* r : todo) {
    auto& world = worlds[world_key(r->scenario)];
    if (!world) world = std::make_shared<const World>(r->scenario.world);
    check_scenario_world(r->scenario, *world);
  }
  std::error_code ec;
  fs::create_directories(runs_dir, ec);
  if (ec) throw InputError(out_dir, "", "cannot create output directory: " + ec.message());
  std::map<std::uint64_t, std::shared_future<std::shared_ptr<const ReferenceTrack>>> references;
  // References are computed lazily by the first worker that needs one; the others wait for it.
  std::mutex mutex;
  auto reference_for = [&](const Scenario& sc, const World& world) {
    std::promise<std::shared_ptr<const ReferenceTrack>> promise;
    std::shared_future<std::shared_ptr<const ReferenceTrack>> future;
    bool mine_to_build = false;
    {
      std::lock_guard lock(mutex);
      auto it = references.find(sc.reference_hash());
      if (it == references.end()) {
        future = promise.get_future().share();
        references.emplace(sc.reference_hash(), future);
        mine_to_build = true;
      } else {
        future = it->second;
      }
    }
    if (mine_to_build) {
      try {
        promise.set_value(compute_reference_track(sc, world));
      } catch (...) {
        promise.set_exception(std::current_exception());  // waiters see the same error
      }
    }
    return future.get();
  };

  // Execution order (the outputs do not depend on it): round robin over the reference
  // variants, i.e. the first run of every variant, then the second of every variant, ... so
  // that parallel workers compute different references at once instead of waiting for the one
  // reference their neighbour is computing.
  {
    std::map<std::uint64_t, std::size_t> group_of;
    std::vector<std::size_t> count;
    std::vector<std::pair<std::pair<std::size_t, std::size_t>, const RunSpec*>> keyed;
    for (const RunSpec* r : todo) {
      const auto [it, added] = group_of.try_emplace(r->scenario.reference_hash(), count.size());
      if (added) count.push_back(0);
      keyed.push_back({{count[it->second]++, it->second}, r});
    }
    std::stable_sort(keyed.begin(), keyed.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    for (std::size_t k = 0; k < todo.size(); ++k) todo[k] = keyed[k].second;
  }
  // What summary.csv needs of each run executed here, kept in memory (reading 234 result.json
  // files back, series included, took 0.8 s of serial time); resumed runs are read from disk.
  std::vector<std::optional<nlohmann::ordered_json>> fresh(all.size());
  std::atomic<std::size_t> next{0};
  std::size_t done = 0;
  const auto t0 = std::chrono::steady_clock::now();
  std::exception_ptr failure;
  auto worker = [&] {
    while (true) {
      if (options.stop && options.stop->load()) return;
      {
        std::lock_guard lock(mutex);
        if (failure) return;
      }
      const std::size_t k = next.fetch_add(1);
      if (k >= todo.size()) return;
      const RunSpec& r = *todo[k];
      try {
        const World* world = worlds.at(world_key(r.scenario)).get();
        const auto reference = reference_for(r.scenario, *world);
        auto planner = factory(r.planner);
        const RunResult result = simulate(r.scenario, *world, *reference, *planner);
        write_run_output((runs_dir / r.id).string(), r.scenario,
                         {planner->name(), planner->params(), run_json(r)}, result,
                         Overwrite::allow);
        nlohmann::ordered_json row;
        row["planner"]["params"] = planner->params();
        row["scenario"]["hash"] = hex64(r.scenario.hash());
        row["summary"] = RunMetrics::to_json(result.summary);
        row["timing"] = result.timing.to_json();
        std::lock_guard lock(mutex);
        fresh[r.index] = std::move(row);
      } catch (...) {
        std::lock_guard lock(mutex);
        if (!failure) failure = std::current_exception();
        return;
      }
      std::lock_guard lock(mutex);
      ++done;
      ++report.executed;
      if (options.progress) {
        const double elapsed =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        const double eta =
            elapsed / static_cast<double>(done) * static_cast<double>(todo.size() - done);
        options.progress(done + report.skipped, report.total, eta, r.id);
      }
    }
  };
  const int jobs = std::max(1, std::min<int>(options.jobs, static_cast<int>(todo.size())));
  std::vector<std::thread> threads;
  for (int j = 1; j < jobs; ++j) threads.emplace_back(worker);
  worker();
  for (auto& t : threads) t.join();
  if (failure) std::rethrow_exception(failure);
  report.interrupted =
      options.stop && options.stop->load() && report.executed + report.skipped < report.total;

  // summary.csv and timing.csv from every finished run of the whole sweep, in sweep order.
  std::string summary, timing;
  std::vector<std::string> summary_header, timing_header;
  for (const auto& r : all) {
    auto j = std::move(fresh[r.index]);
    if (!j) {
      j = read_result(runs_dir / r.id / "result.json");
      if (!j || !j->contains("run") || (*j)["run"].value("hash", "") != hex64(r.run_hash)) continue;
    }
    std::vector<std::pair<std::string, std::string>> cols = {
        {"run", r.id},
        {"scenario", r.scenario.name},
        {"planner", r.planner.name},
        {"label", r.planner.label},
        {"params", csv_escape((*j)["planner"]["params"].dump())},
        {"faces_per_frame", format_number(r.budget)},
        {"speed_scale", format_number(r.speed_scale)},
        {"fps", format_number(r.fps)},
        {"seed", std::to_string(r.seed)},
        {"scenario_hash", (*j)["scenario"].value("hash", "")}};
    flatten((*j)["summary"], "", cols);
    if (summary_header.empty()) {
      for (const auto& c : cols) summary_header.push_back(c.first);
      for (std::size_t i = 0; i < summary_header.size(); ++i) {
        summary += (i ? "," : "") + summary_header[i];
      }
      summary += "\n";
    }
    for (std::size_t i = 0; i < cols.size(); ++i) summary += (i ? "," : "") + cols[i].second;
    summary += "\n";
    std::vector<std::pair<std::string, std::string>> tcols = {{"run", r.id}};
    if (j->contains("timing")) flatten((*j)["timing"], "timing", tcols);
    if (timing_header.empty()) {
      for (const auto& c : tcols) timing_header.push_back(c.first);
      for (std::size_t i = 0; i < tcols.size(); ++i) timing += (i ? "," : "") + tcols[i].first;
      timing += "\n";
    }
    for (std::size_t i = 0; i < tcols.size(); ++i) timing += (i ? "," : "") + tcols[i].second;
    timing += "\n";
  }
  write_text_atomically((fs::path(out_dir) / "summary.csv").string(), summary, Overwrite::allow);
  write_text_atomically((fs::path(out_dir) / "timing.csv").string(),
                        "# measured wall-clock times: not deterministic, not results\n" + timing,
                        Overwrite::allow);
  return report;
}

}  // namespace ambisim
