#include "policies/registry/presets.h"

#include <stdexcept>

#include "policies/registry/presets_data.h"  // generated from presets.json at build time
#include "sim/base/input_error.h"

namespace ambisim {

const nlohmann::json& all_presets() {
  static const nlohmann::json presets = [] {
    nlohmann::json j = nlohmann::json::parse(kPresetsJson);
    if (!j.is_object()) throw std::logic_error("presets.json: not an object");
    return j;
  }();
  return presets;
}

std::vector<std::string> preset_names() {
  std::vector<std::string> out;
  for (const auto& [name, v] : all_presets().items()) {
    if (name.front() != '_') out.push_back(name);  // "_comment" keys document the file
  }
  return out;
}

const nlohmann::json& preset_params(const std::string& planner, const std::string& preset,
                                    const std::string& file, const std::string& path) {
  const nlohmann::json& all = all_presets();
  const auto it = all.find(preset);
  if (preset.empty() || preset.front() == '_' || it == all.end()) {
    std::string valid;
    for (const auto& n : preset_names()) valid += (valid.empty() ? "" : ", ") + n;
    throw InputError(file, path, "unknown preset \"" + preset + "\"; valid presets: " + valid);
  }
  const auto p = it->find(planner);
  if (p == it->end()) {
    throw std::logic_error("preset \"" + preset + "\" has no entry for planner \"" + planner +
                           "\"");
  }
  return (*p)["params"];
}

}  // namespace ambisim
