#pragma once
// Inputs shared by the planner tests: every shipped scenario cut short with a cheap reference,
// one World per world description, and the small unit-test drive.
#include <memory>
#include <string>
#include <vector>

#include "policies/registry/registry.h"
#include "sim/run/reference_track.h"
#include "sim/scenario/scenario.h"
#include "sim/world/world.h"

namespace ambisim::test {

inline const std::string kSmallDrive =
    std::string(AMBISIM_SOURCE_DIR) + "/tests/data/small_drive.json";

// Every scenario file under scenarios/ (sorted by path), cut to its first `seconds` with an
// 8x8 reference on a 0.1 s grid (scoring the sample the file asks for, if any);
// tests/data/small_drive.json appended when asked.
std::vector<Scenario> short_scenarios(double seconds, bool with_small_drive = false);

// The world of a scenario, built once per world description for the whole test binary: keyed
// by its whole "world" section and its seed (a World carries its terrain and its lighting,
// so two scenarios share one only when both are the same).
const World& world_for(const Scenario& sc);

// A planner by name at its defaults, except a bake (the baked planners' preload) bounded to
// kTestBakeCaptures captures at kTestBakeFaceSize: a full bake of a scenario's route and
// traffic is tens of thousands of 24x24 captures, minutes in every test that runs every
// planner over every scenario; the contract holds for any bake size.
inline constexpr std::int64_t kTestBakeCaptures = 3000;
inline constexpr int kTestBakeFaceSize = 8;
std::unique_ptr<Planner> make_test_planner(const std::string& name,
                                           std::int64_t bake_captures = kTestBakeCaptures);

// tests/data/small_drive.json with its world and its full (every-frame) reference.
struct SmallDrive {
  Scenario scenario = load_scenario(kSmallDrive);
  World world{scenario.world};
  std::shared_ptr<const ReferenceTrack> reference = compute_reference_track(scenario, world);
};

}  // namespace ambisim::test
