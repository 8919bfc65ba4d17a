#include "sim/scenario/scenario_file.h"

#include "sim/base/json_reader.h"

namespace ambisim {

WorldParams load_world_params(const std::string& path) {
  const nlohmann::json doc = load_json_file(path);
  ObjectReader root(doc, path, "");
  auto world = root.object("world");
  WorldParams params = parse_world_params(world);
  world.finish();
  return params;
}

}  // namespace ambisim
