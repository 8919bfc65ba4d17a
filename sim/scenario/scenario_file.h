#pragma once
// Loading scenario files. A scenario is one JSON document whose "world" object describes the
// world; the simulation sections are read by the full scenario parser (sim/scenario/scenario.h).
#include <string>

#include "sim/world/world_params.h"

namespace ambisim {

// Reads only the "world" object of a scenario file (other top-level sections are left to the
// full scenario parser), with strict key checking inside it.
WorldParams load_world_params(const std::string& path);

}  // namespace ambisim
