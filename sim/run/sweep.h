#pragma once
// Sweeps: the cartesian product scenarios x planners x budgets x camera speeds x frame rates x
// seeds, one run each. A sweep file is parsed into a SweepSpec, expanded into RunSpecs (each a
// scenario variant document plus a planner), and executed by run_sweep() in parallel over
// runs. Results are byte-identical for any thread count and order: every run is
// single-threaded and deterministic, and summary.csv is written in the sweep's own order.
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sim/planner.h"
#include "sim/scenario/scenario.h"

namespace ambisim {

struct SweepPlanner {
  std::string name;
  std::string label;           // unique within the sweep; defaults to the name
  nlohmann::json params;       // object, validated by the planner factory
  std::string params_pointer;  // JSON path of the params in the sweep file (for errors)
  std::string preset;          // a named parameter set under params ("" = none), e.g. "tuned"
  std::string preset_pointer;  // its JSON path
};

struct SweepSpec {
  std::string file;
  std::string name;
  std::vector<std::string> scenarios;  // paths, resolved relative to the sweep file
  std::vector<SweepPlanner> planners;
  std::vector<double> budgets{1.0};       // faces per frame
  std::vector<double> speed_scales{1.0};  // multiplies the camera's speeds
  std::vector<double> fps;                // empty: each scenario's own frame-rate schedule
  std::vector<std::uint64_t> seeds;       // world seeds (apply_seed); empty: the scenario's own
  std::optional<double> duration_s;       // overrides every scenario's duration
  nlohmann::json overrides = nlohmann::json::object();  // JSON pointer -> value, for every run
};

// Parses a sweep document; `path` names it in errors and scenario paths are resolved relative
// to its directory (the scenario files must exist). Unknown keys are errors.
SweepSpec parse_sweep(const nlohmann::json& doc, const std::string& path);

// Loads and parses a sweep file.
SweepSpec load_sweep(const std::string& path);

struct RunSpec {
  std::size_t index = 0;  // position in the sweep's order
  std::string id;         // directory name under runs/, from the parameters
  Scenario scenario;      // the variant
  SweepPlanner planner;
  double budget = 1.0;
  double speed_scale = 1.0;
  double fps = 0.0;  // 0: the scenario's own
  std::uint64_t seed = 0;
  std::uint64_t run_hash = 0;  // scenario variant hash + planner + params
};

std::vector<RunSpec> expand_sweep(const SweepSpec& spec);

// One seed of a sweep's `seeds`: the world is generated from `seed`, and the receivers from a
// seed derived from the scenario's own receiver seed and `seed` (hash-mixed), except that the
// scenario's own world seed keeps its receiver seed too: that seed runs the scenario as written.
// Scenario positions that name landmarks (landmark_ref.h) follow the world.
void apply_seed(nlohmann::json& doc, std::uint64_t seed, const std::string& file);

// Builds a planner by name from a JSON params object (the policies registry; injected so that
// sim/ does not depend on policies/).
using PlannerFactory = std::function<std::unique_ptr<Planner>(const SweepPlanner&)>;

struct SweepOptions {
  int jobs = 1;
  int shard_index = 0;  // 0-based
  int shard_count = 1;
  bool resume = false;
  bool force = false;
  // Progress lines (done, total, eta seconds, current run id); called from worker threads under
  // a lock.
  std::function<void(std::size_t, std::size_t, double, const std::string&)> progress;
  const std::atomic<bool>* stop = nullptr;  // set by a SIGINT handler: finish runs, start none
};

struct SweepReport {
  std::size_t total = 0;  // runs in this shard
  std::size_t executed = 0;
  std::size_t skipped = 0;  // resumed
  bool interrupted = false;
};

// Runs the sweep into `out_dir` (runs/<id>/result.json, frames.csv; summary.csv; timing.csv).
SweepReport run_sweep(const SweepSpec& spec, const std::string& out_dir,
                      const PlannerFactory& factory, const SweepOptions& options);

}  // namespace ambisim
