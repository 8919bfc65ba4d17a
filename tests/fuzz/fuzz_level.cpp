// libFuzzer target: the level loader (sim/world/terrain_level.h) and its PNG decoder on
// arbitrary bytes. The input is up to four files separated by the line "--ambisim-next--":
// heightmap (a PNG, or a RAW when the input starts with "RAW" and then a width and a height
// byte), albedo, canopy and water. Bad files must end in ambisim::InputError; anything else
// escaping, a crash or a sanitizer report is a finding. A level that loads must build its
// World (small: at most 64 x 64 pixels are let through to the world).
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sim/base/input_error.h"
#include "sim/base/json_reader.h"
#include "sim/world/terrain_level.h"
#include "sim/world/world.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string input(reinterpret_cast<const char*>(data), size);
  const std::string sep = "\n--ambisim-next--\n";
  std::vector<std::string> parts;
  std::size_t pos = 0;
  while (parts.size() < 3) {
    const std::size_t next = input.find(sep, pos);
    if (next == std::string::npos) break;
    parts.push_back(input.substr(pos, next - pos));
    pos = next + sep.size();
  }
  parts.push_back(input.substr(pos));
  nlohmann::json doc = {{"cell_m", 2.0}, {"height_scale_m", 100.0}};
  std::map<std::string, std::string> files;
  const char* keys[] = {"heightmap", "albedo", "canopy", "water"};
  for (std::size_t k = 0; k < parts.size(); ++k) {
    std::string name = std::string("levels/") + keys[k] + ".png";
    if (k == 0 && parts[0].size() >= 5 && parts[0].compare(0, 3, "RAW") == 0) {
      name = "levels/heightmap.raw";
      doc["heightmap_size"] = {static_cast<unsigned char>(parts[0][3]),
                               static_cast<unsigned char>(parts[0][4])};
      parts[0] = parts[0].substr(5);
    }
    doc[keys[k]] = name;
    files[name] = parts[k];
  }
  if (doc.contains("canopy")) doc["canopy_scale_m"] = 30.0;
  ambisim::TerrainLevel level;
  try {
    ambisim::ObjectReader r(doc, "fuzz/scene.json", "/world/level");
    level = ambisim::parse_terrain_level(
        r, [&](ambisim::ObjectReader& rr, const std::string& key, const std::string& path) {
          const auto it = files.find(path.substr(path.find("levels/")));
          if (it == files.end()) rr.fail(key, "no such file: " + path);
          return it->second;
        });
  } catch (const ambisim::InputError&) {
    return 0;  // refused with a file and a path: the expected outcome for bad input
  }
  if (level.nx > 64 || level.ny > 64) return 0;
  ambisim::WorldParams p;
  p.cell_m = level.cell_m;
  p.size_m = {level.nx * level.cell_m, level.ny * level.cell_m};
  p.road.enabled = false;
  p.level = std::make_shared<ambisim::TerrainLevel>(level);
  const ambisim::World w(p);
  (void)w.content_hash();
  return 0;
}
