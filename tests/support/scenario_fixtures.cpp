#include "tests/support/scenario_fixtures.h"

#include <algorithm>
#include <filesystem>
#include <map>
#include <memory>

#include "sim/base/json_reader.h"

namespace ambisim::test {

std::vector<Scenario> short_scenarios(double seconds, bool with_small_drive) {
  std::vector<std::string> files;
  for (const auto& e :
       std::filesystem::directory_iterator(std::string(AMBISIM_SOURCE_DIR) + "/scenarios")) {
    if (e.path().extension() == ".json" && e.path().stem() != "default_world") {
      files.push_back(e.path().string());
    }
  }
  std::sort(files.begin(), files.end());
  std::vector<Scenario> out;
  for (const auto& f : files) {
    nlohmann::json doc = load_json_file(f);
    doc["frames"]["duration_s"] = seconds;
    // A game's load keeps its sample (it scores every k-th receiver of thousands).
    const nlohmann::json stride =
        doc.value("reference", nlohmann::json::object()).value("sample_stride", nlohmann::json(1));
    doc["reference"] = {{"face_size", 8}, {"interval_s", 0.1}, {"sample_stride", stride}};
    out.push_back(parse_scenario(doc, f));
  }
  if (with_small_drive) out.push_back(load_scenario(kSmallDrive));
  return out;
}

const World& world_for(const Scenario& sc) {
  static std::map<std::string, std::unique_ptr<World>> cache;
  const std::string key =
      nlohmann::json{{"seed", sc.world.seed},
                     {"world", sc.document.value("world", nlohmann::json::object())}}
          .dump();
  auto& slot = cache[key];
  if (!slot) slot = std::make_unique<World>(sc.world);
  return *slot;
}

std::unique_ptr<Planner> make_test_planner(const std::string& name, std::int64_t bake_captures) {
  std::vector<std::string> sets;
  for (const auto& info : planner_catalogue()) {
    if (info.name != name) continue;
    for (const auto& p : info.params) {
      if (p.name == "max_captures") sets.push_back("max_captures=" + std::to_string(bake_captures));
      if (p.name == "bake_face_size")
        sets.push_back("bake_face_size=" + std::to_string(kTestBakeFaceSize));
    }
  }
  return make_planner(name, planner_params_from_cli(name, sets));
}

}  // namespace ambisim::test
