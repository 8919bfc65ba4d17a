// Every scenario and sweep file the repository ships loads, expands and names only registered
// planners and parameters: a renamed parameter must break here, not in a user's hour-long sweep.
#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>

#include "policies/registry/registry.h"
#include "sim/run/sweep.h"
#include "sim/scenario/scenario.h"

using namespace ambisim;

namespace {
std::vector<std::string> json_files(const std::string& dir) {
  std::vector<std::string> out;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    if (e.path().extension() == ".json") out.push_back(e.path().string());
  }
  std::sort(out.begin(), out.end());
  return out;
}
}  // namespace

TEST_CASE("every shipped sweep file expands to runs of registered planners", "[files]") {
  const std::string root = std::string(AMBISIM_SOURCE_DIR) + "/scenarios";
  std::vector<std::string> files = json_files(root + "/sweeps");
  for (const auto& f : json_files(root + "/stress/sweeps")) files.push_back(f);
  REQUIRE(files.size() >= 4);
  for (const auto& file : files) {
    INFO(file);
    const SweepSpec spec = load_sweep(file);
    const std::vector<RunSpec> runs = expand_sweep(spec);
    CHECK(runs.size() >= spec.planners.size());
    for (const SweepPlanner& p : spec.planners) {
      CHECK_NOTHROW(make_planner(
          p.name, planner_params_from_json(p.name, p.params, spec.file, p.params_pointer)));
    }
  }
}
