// Scenario positions that name a landmark of the world: parsed, resolved against the built
// world, refused when unknown or absent, and seed-independent by construction.
#include <catch2/catch.hpp>
#include <string>

#include "sim/base/input_error.h"
#include "sim/run/sweep.h"
#include "sim/scenario/scenario.h"
#include "sim/world/landmarks.h"
#include "sim/world/world.h"

using namespace ambisim;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;
using nlohmann::json;

namespace {

// A 1 km world with a forest edge (seed 1); its scenario flies toward the edge.
json flight(const json& points, bool road = true) {
  json d = json::parse(R"({
    "world": {"seed": 1, "size_m": [1024, 1024]},
    "camera": {"type": "keyframes", "z_mode": "above_ground", "speed_mps": 20},
    "frames": {"fps": 30, "duration_s": 1},
    "receivers": {"camera_object": {"ahead_m": 4}},
    "reference": {"face_size": 8}
  })");
  d["camera"]["points"] = points;
  if (!road) d["world"]["road"] = {{"enabled", false}};
  return d;
}

std::string parse_error(const json& d) {
  try {
    (void)parse_scenario(d, "s.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

const World& world_of(const Scenario& s) {
  static const World w(s.world);
  return w;
}

}  // namespace

TEST_CASE("a keyframe may name a landmark: its frame plus the offset", "[scenario][landmarks]") {
  const json pts = json::parse(R"([{"landmark": "forest_edge", "offset": [-200, 10, 6]},
                                   {"landmark": "forest_edge", "offset": [50, -5, 20]},
                                   [400, 400, 30]])");
  const Scenario s = parse_scenario(flight(pts), "s.json");
  const World& w = world_of(s);
  REQUIRE(w.landmarks().forest_edge.found);
  const auto frame = landmark_frame(w.landmarks(), "forest_edge");
  REQUIRE(frame);
  const CameraPathRecord c = resolved_camera(s, w);
  // z_mode above_ground: x, y from the frame, z the offset's height above the ground.
  const glm::dvec3 p0 = frame->point({-200, 10, 6});
  CHECK(c.points[0].x == p0.x);
  CHECK(c.points[0].y == p0.y);
  CHECK(c.points[0].z == 6.0);
  // along, left: 10 m to the left is along turned counter-clockwise.
  const glm::dvec2 left(-frame->along.y, frame->along.x);
  CHECK(c.points[0].x == Approx(frame->origin.x - 200 * frame->along.x + 10 * left.x));
  CHECK(c.points[1].z == 20.0);
  CHECK(c.points[2] == glm::dvec3(400, 400, 30));  // coordinates stay as written
  CHECK_NOTHROW(check_scenario_world(s, w));
}

TEST_CASE("an unknown landmark is refused when read, listing the valid names",
          "[scenario][landmarks]") {
  const json pts = json::parse(R"([{"landmark": "forest_egde"}, [0, 0, 10]])");
  const std::string e = parse_error(flight(pts));
  CHECK_THAT(e, StartsWith("s.json: /camera/points/0/landmark: unknown landmark \"forest_egde\""));
  CHECK_THAT(e, Contains("valid landmarks: forest_edge, road.deepest_cutting, "
                         "road.highest_embankment, rock_outcrop, cliff"));
  CHECK_THAT(
      parse_error(flight(json::parse(R"([{"landmark": "cliff", "ofset": [0,0,0]}, [0,0,1]])"))),
      StartsWith("s.json: /camera/points/0/ofset: unknown key"));
}

TEST_CASE("a landmark the world lacks is refused before anything runs", "[scenario][landmarks]") {
  const json pts = json::parse(R"([[100, 100, 10], {"landmark": "road.deepest_cutting"}])");
  const Scenario s = parse_scenario(flight(pts, false), "s.json");
  const World w(s.world);
  try {
    check_scenario_world(s, w);
    FAIL("no error");
  } catch (const InputError& e) {
    CHECK_THAT(std::string(e.what()),
               StartsWith("s.json: /camera/points/1/landmark: this world (its seed and "
                          "settings) has no road.deepest_cutting"));
  }
}

TEST_CASE("a sweep seed moves the world and the receivers, the scenario's own seed keeps both",
          "[scenario][sweep]") {
  json doc = {{"world", {{"seed", 1}}}, {"receivers", {{"seed", 11}}}};
  json own = doc;
  apply_seed(own, 1, "s.json");
  CHECK(own["world"]["seed"] == 1);
  CHECK(own["receivers"]["seed"] == 11);
  json other = doc;
  apply_seed(other, 4, "s.json");
  CHECK(other["world"]["seed"] == 4);
  const auto r4 = other["receivers"]["seed"].get<std::uint64_t>();
  CHECK(r4 != 11);
  CHECK(r4 < (std::uint64_t{1} << 53));  // an exact JSON number
  json again = doc;
  apply_seed(again, 4, "s.json");
  CHECK(again == other);  // deterministic
  json five = doc;
  apply_seed(five, 5, "s.json");
  CHECK(five["receivers"]["seed"] != other["receivers"]["seed"]);
  // Sections without seeds: the defaults (1) are the scenario's own.
  json bare = json::object();
  apply_seed(bare, 1, "s.json");
  CHECK(bare["receivers"]["seed"] == 1);
}
