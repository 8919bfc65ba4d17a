// libFuzzer target: the sweep parser on arbitrary bytes read as JSON, then (for small sweeps)
// the expansion into runs, which applies the sweep's overrides to the real scenario files and
// parses every variant, and the planner registry's validation of every planner's parameters.
// The document is parsed as if it lived in scenarios/sweeps/, so "../motorway.json" resolves.
// Bad input must end in ambisim::InputError; anything else is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "policies/registry/registry.h"
#include "sim/base/input_error.h"
#include "sim/run/sweep.h"

#ifndef AMBISIM_SOURCE_DIR
#error "AMBISIM_SOURCE_DIR must be defined"
#endif

namespace {
// Expanding parses one scenario per variant: keep each input fast.
constexpr std::size_t kMaxVariants = 32;
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception&) {
    return 0;
  }
  const std::string file = AMBISIM_SOURCE_DIR "/scenarios/sweeps/fuzz.json";
  try {
    const ambisim::SweepSpec spec = ambisim::parse_sweep(doc, file);
    for (const auto& p : spec.planners) {
      (void)ambisim::make_planner(
          p.name, ambisim::planner_params_from_json(p.name, p.params, spec.file, p.params_pointer));
    }
    const std::size_t variants =
        spec.scenarios.size() * spec.budgets.size() * spec.speed_scales.size() *
        std::max<std::size_t>(1, spec.fps.size()) * std::max<std::size_t>(1, spec.seeds.size());
    if (variants <= kMaxVariants) (void)ambisim::expand_sweep(spec);
  } catch (const ambisim::InputError&) {
    return 0;
  }
  return 0;
}
