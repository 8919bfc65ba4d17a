#pragma once
// What a planner family tells the registry about each planner it offers: its name, a one-line
// description, its parameters and how to build it. Each family includes this (and core only);
// policies/registry/ lists every family's planners, above them all.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "policies/core/planner_params.h"
#include "sim/planner.h"

namespace ambisim {

struct PlannerInfo {
  std::string name;
  std::string description;  // one line, for `ambisim planners`
  std::vector<ParamSpec> params;
  // Builds the planner from parameters already bound to `params` (defaults filled).
  std::function<std::unique_ptr<Planner>(const PlannerParams&)> make;
};

}  // namespace ambisim
