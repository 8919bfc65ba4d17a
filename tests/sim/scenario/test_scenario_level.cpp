// A scenario importing a level (sim/world/terrain_level.h): its images are found relative to
// the scenario file, and the scenario's hashes follow their bytes although the document names
// the same files.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>

#include "sim/base/json_reader.h"
#include "sim/base/png_codec.h"
#include "sim/scenario/scenario.h"
#include "sim/world/world.h"

using namespace ambisim;

namespace {

void write_file(const std::filesystem::path& p, const std::string& bytes) {
  std::ofstream out(p, std::ios::binary);
  out << bytes;
}

std::string heightmap_png(std::uint16_t corner) {
  PngSamples h;
  h.width = 16;
  h.height = 16;
  h.channels = 1;
  h.bit_depth = 16;
  h.samples.assign(256, 1000);
  h.samples[0] = corner;
  return encode_png(h);
}

}  // namespace

TEST_CASE("scenario: a level's images resolve next to the scenario and feed its hashes",
          "[scenario][level]") {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / "ambisim_test_scenario_level";
  fs::remove_all(dir);
  fs::create_directories(dir / "levels" / "t");
  const nlohmann::json doc = {
      {"world",
       {{"level", {{"heightmap", "levels/t/h.png"}, {"cell_m", 4}, {"height_scale_m", 100}}},
        {"sky", {{"model", "gradient"}}}}},
      {"camera", {{"points", {{10, 10, 50}, {50, 50, 50}}}, {"speed_mps", 5}}},
      {"frames", {{"fps", 30}, {"duration_s", 1}}}};
  write_file(dir / "scene.json", doc.dump());
  write_file(dir / "levels" / "t" / "h.png", heightmap_png(1000));
  const Scenario a = load_scenario((dir / "scene.json").string());
  REQUIRE(a.world.level);
  CHECK(a.world.size_m == glm::dvec2(64.0, 64.0));
  CHECK_FALSE(a.world.road.enabled);
  const Scenario same = load_scenario((dir / "scene.json").string());
  CHECK(same.hash() == a.hash());
  // The top-left pixel is the north-west cell (0, 15).
  write_file(dir / "levels" / "t" / "h.png", heightmap_png(2000));
  const Scenario b = load_scenario((dir / "scene.json").string());
  CHECK(b.document == a.document);
  CHECK(b.hash() != a.hash());
  CHECK(b.reference_hash() != a.reference_hash());
  const World wa(a.world), wb(b.world);
  CHECK(wb.column_ground(0, 15) == static_cast<float>(2000 / 65535.0 * 100.0));
  CHECK(wa.column_ground(0, 15) == static_cast<float>(1000 / 65535.0 * 100.0));
  CHECK(wa.content_hash() != wb.content_hash());
  fs::remove_all(dir);
}
