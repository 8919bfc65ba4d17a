#pragma once
// The planner registry: every planner the CLI, sweeps and the contract test can build, by name.
// Registration is explicit (one line per planner in registry.cpp, in catalogue order) rather
// than by static self-registering objects, which a static library's linker may silently drop.
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "policies/core/planner_info.h"
#include "policies/core/planner_params.h"
#include "sim/planner.h"

namespace ambisim {

// All registered planners, in a fixed order.
const std::vector<PlannerInfo>& planner_catalogue();

// The entry for `name`; an unknown name is an InputError (at file/path, if given) listing the
// valid names.
const PlannerInfo& find_planner(const std::string& name, const std::string& file = "",
                                const std::string& path = "");

// Parameters for `name` from a JSON object or `--set key=value` strings (validated now), over
// a preset's values when `preset` is given (presets.h; explicit values win).
PlannerParams planner_params_from_json(const std::string& name, const nlohmann::json& j,
                                       const std::string& file, const std::string& pointer,
                                       const std::string& preset = "",
                                       const std::string& preset_pointer = "");
PlannerParams planner_params_from_cli(const std::string& name,
                                      const std::vector<std::string>& assignments,
                                      const std::string& preset = "");

// Builds `name`. `params` may be default-constructed (all defaults) or built for this planner;
// its explicit values are re-validated against this planner's specs either way.
std::unique_ptr<Planner> make_planner(const std::string& name,
                                      const PlannerParams& params = PlannerParams());

// Human-readable catalogue: each planner, its description, and a table of its parameters.
std::string format_catalogue(const std::vector<PlannerInfo>& catalogue = planner_catalogue());
// Machine-readable catalogue (for tools and results).
nlohmann::json catalogue_json(const std::vector<PlannerInfo>& catalogue = planner_catalogue());

}  // namespace ambisim
