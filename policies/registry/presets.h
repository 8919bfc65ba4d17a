#pragma once
// Named parameter sets per planner (`--preset tuned` on `run`, `"preset": "tuned"` in sweeps).
// A preset is data: policies/registry/presets.json, compiled in. The `tuned` preset of every
// planner is written by scripts/tune.py from the equal tuning sweep (scenarios/tuning/): each
// planner's best of the same number of configurations on the training scenarios, so no planner
// is compared at defaults against another tuned step by step.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace ambisim {

// The preset names any planner has, sorted.
std::vector<std::string> preset_names();
// The parameter values of `preset` for `planner` (an object; empty when the preset keeps every
// default). An unknown preset is an InputError at file/path listing the valid ones; a known
// preset without an entry for the planner is a programming error (the test checks every
// planner has one).
const nlohmann::json& preset_params(const std::string& planner, const std::string& preset,
                                    const std::string& file = "", const std::string& path = "");
// Every preset, as stored.
const nlohmann::json& all_presets();

}  // namespace ambisim
