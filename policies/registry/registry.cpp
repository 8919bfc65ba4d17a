#include "policies/registry/registry.h"

#include <algorithm>
#include <sstream>

#include "policies/ambisim/demand_planner.h"
#include "policies/baselines/baked.h"
#include "policies/baselines/cascades.h"
#include "policies/baselines/constant_ambient.h"
#include "policies/baselines/nearest_probe.h"
#include "policies/baselines/oracle.h"
#include "policies/baselines/per_object.h"
#include "policies/baselines/relit.h"
#include "policies/baselines/scrolling_grid.h"
#include "policies/registry/presets.h"
#include "policies/thesis/octree.h"
#include "policies/thesis/shgraph.h"
#include "policies/thesis/shgraph2d.h"
#include "sim/base/input_error.h"

namespace ambisim {

const std::vector<PlannerInfo>& planner_catalogue() {
  // One line per planner (later: octree, shgraph, their +vp variants, shgraph2d, per_object,
  // grid, ambisim's own). Order = the order `ambisim planners` prints.
  static const std::vector<PlannerInfo> catalogue = {
      OraclePlanner::info(),
      ConstantAmbientPlanner::constant_info(),
      ConstantAmbientPlanner::hemisphere_info(),
      NearestProbePlanner::info(),
      PerObjectPlanner::info(),
      ScrollingGridPlanner::info(),
      CascadesPlanner::info(),
      RelitPlanner::info(),
      BakedPlanner::baked_info(),
      BakedPlanner::tod_info(),
      OctreePlanner::info(),
      OctreePlanner::vp_info(),
      ShGraphPlanner::info(),
      ShGraphPlanner::info_vp(),
      ShGraphPlanner::info_route(),
      ShGraph2dPlanner::info(),
      DemandPlanner::info(),
  };
  return catalogue;
}

const PlannerInfo& find_planner(const std::string& name, const std::string& file,
                                const std::string& path) {
  const auto& all = planner_catalogue();
  for (const auto& info : all) {
    if (info.name == name) return info;
  }
  std::string valid;
  for (const auto& info : all) valid += (valid.empty() ? "" : ", ") + info.name;
  throw InputError(file, path, "unknown planner \"" + name + "\"; valid planners: " + valid);
}

namespace {

// A preset's values for the parameters not given explicitly (explicit values win).
void apply_preset(PlannerParams& p, const std::string& preset, const std::string& file,
                  const std::string& pointer) {
  if (preset.empty()) return;
  const std::string where = "presets.json: /" + preset + "/" + p.planner() + "/params";
  for (const auto& [k, v] : preset_params(p.planner(), preset, file, pointer).items()) {
    if (!p.is_set(k)) p.set_json(k, v, where, "/" + k);
  }
}

}  // namespace

PlannerParams planner_params_from_json(const std::string& name, const nlohmann::json& j,
                                       const std::string& file, const std::string& pointer,
                                       const std::string& preset,
                                       const std::string& preset_pointer) {
  const PlannerInfo& info = find_planner(name, file, pointer);
  PlannerParams p = PlannerParams::from_json(info.name, info.params, j, file, pointer);
  apply_preset(p, preset, file, preset_pointer);
  return p;
}

PlannerParams planner_params_from_cli(const std::string& name,
                                      const std::vector<std::string>& assignments,
                                      const std::string& preset) {
  const PlannerInfo& info = find_planner(name, "--planner", "");
  PlannerParams p = PlannerParams::from_cli(info.name, info.params, assignments);
  apply_preset(p, preset, "--preset", "");
  return p;
}

std::unique_ptr<Planner> make_planner(const std::string& name, const PlannerParams& params) {
  const PlannerInfo& info = find_planner(name);
  return info.make(params.bind(info.name, info.params));
}

std::string format_catalogue(const std::vector<PlannerInfo>& catalogue) {
  std::ostringstream os;
  for (const auto& info : catalogue) {
    os << info.name << ": " << info.description << "\n";
    // The presets first: what `--preset NAME` sets (nothing: the defaults).
    for (const auto& preset : preset_names()) {
      std::string values;
      for (const auto& [k, v] : preset_params(info.name, preset).items()) {
        values += (values.empty() ? "" : ", ") + k + "=" +
                  (v.is_string() ? v.get<std::string>() : v.dump());
      }
      os << "    preset " << preset << ": " << (values.empty() ? "the defaults" : values) << "\n";
    }
    if (info.params.empty()) {
      os << "    (no parameters)\n";
      continue;
    }
    std::size_t w_name = 0, w_type = 0, w_def = 0, w_allowed = 0;
    std::vector<std::string> defs;
    for (const auto& s : info.params) {
      defs.push_back(s.default_text());
      w_name = std::max(w_name, s.name.size());
      w_type = std::max(w_type, to_string(s.type).size());
      w_def = std::max(w_def, defs.back().size());
      w_allowed = std::max(w_allowed, s.allowed_text().size());
    }
    for (std::size_t i = 0; i < info.params.size(); ++i) {
      const auto& s = info.params[i];
      auto pad = [](const std::string& t, std::size_t w) {
        return t + std::string(w - t.size(), ' ');
      };
      os << "    " << pad(s.name, w_name) << "  " << pad(to_string(s.type), w_type) << "  "
         << pad(defs[i], w_def) << "  " << pad(s.allowed_text(), w_allowed) << "  " << s.description
         << "\n";
    }
  }
  return os.str();
}

nlohmann::json catalogue_json(const std::vector<PlannerInfo>& catalogue) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& info : catalogue) {
    nlohmann::json params = nlohmann::json::array();
    for (const auto& s : info.params) params.push_back(s.to_json());
    nlohmann::json presets = nlohmann::json::object();
    for (const auto& preset : preset_names()) presets[preset] = preset_params(info.name, preset);
    out.push_back({{"name", info.name},
                   {"description", info.description},
                   {"params", params},
                   {"presets", presets}});
  }
  return out;
}

}  // namespace ambisim
