// Scenario and sweep parsing refuses absurd values and inconsistent sections with an InputError
// naming the JSON path, before anything is built (regressions of tests/cli/bad_input.sh and
// of fuzzing findings, tests/fuzz).
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include <catch2/catch.hpp>

#include "sim/base/input_error.h"
#include "sim/run/sweep.h"
#include "sim/scenario/scenario.h"
#include "sim/world/world.h"

using ambisim::InputError;
using nlohmann::json;

namespace {

json small_scenario() {
  return json::parse(R"({
    "world": {"seed": 3, "size_m": [256, 256], "cell_m": 4, "road": {"meander_m": 30}},
    "camera": {"type": "road", "start_arc_length_m": 10, "speed_mps": 20},
    "frames": {"fps": 30, "duration_s": 1},
    "budget": {"faces_per_frame": 1, "face_size": 8},
    "receivers": {"traffic": {"rate_per_s": 4, "max_live": 6}},
    "reference": {"face_size": 8}
  })");
}

// The InputError message of parsing `doc`, or "no error".
std::string error_of(const json& doc) {
  try {
    (void)ambisim::parse_scenario(doc, "s.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

std::string error_with(const std::function<void(json&)>& change) {
  json d = small_scenario();
  change(d);
  return error_of(d);
}

}  // namespace

TEST_CASE("the small test scenario parses", "[scenario]") {
  CHECK(error_of(small_scenario()) == "no error");
}

TEST_CASE("absurd sizes and rates are refused by range checks", "[scenario]") {
  using Catch::Matchers::StartsWith;
  CHECK_THAT(error_with([](json& d) {
               d["world"]["size_m"] = {1e9, 1e9};
             }),
             StartsWith("s.json: /world/size_m/0: must be <= 65536"));
  CHECK_THAT(error_with([](json& d) {
               d["world"]["size_m"] = {16384, 16384};
               d["world"]["cell_m"] = 1;
             }),
             StartsWith("s.json: /world/cell_m: too small for size_m: at most 67108864"));
  CHECK_THAT(error_with([](json& d) { d["frames"]["fps"] = 1e9; }),
             StartsWith("s.json: /frames/fps: must be <= 10000"));
  CHECK_THAT(error_with([](json& d) { d["frames"]["duration_s"] = 1e12; }),
             StartsWith("s.json: /frames/duration_s: must be <= 86400"));
  CHECK_THAT(error_with([](json& d) {
               d["frames"]["duration_s"] = 3600;
               d["frames"]["fps"] = 1000;
             }),
             StartsWith("s.json: /frames/duration_s: gives 3600000 frames"));
  CHECK_THAT(error_with([](json& d) { d["budget"]["face_size"] = 1000000; }),
             StartsWith("s.json: /budget/face_size: must be <= 1024"));
  CHECK_THAT(error_with([](json& d) { d["receivers"]["traffic"]["max_live"] = 1000000000; }),
             StartsWith("s.json: /receivers/traffic/max_live: must be <= 10000"));
  CHECK_THAT(error_with([](json& d) {
               d["world"]["sky"] = {{"model", "gradient"}, {"zenith", {1e300, 1, 1}}};
             }),
             StartsWith("s.json: /world/sky/zenith/0: must be <= 1000000"));
  CHECK_THAT(error_with([](json& d) { d["camera"]["height_m"] = 1e300; }),
             StartsWith("s.json: /camera/height_m: must be <= 100000"));
}

TEST_CASE("a frame schedule at the frame limit is accepted", "[scenario][frames]") {
  // 1e6 frames exactly: 1000 s at 1000 fps.
  const std::string e = error_with([](json& d) {
    d["frames"]["duration_s"] = 1000;
    d["frames"]["fps"] = 1000;
  });
  CHECK(e == "no error");
}

TEST_CASE("keyframe paths need two distinct, finite-length points", "[scenario][camera]") {
  using Catch::Matchers::StartsWith;
  CHECK_THAT(error_with([](json& d) {
               d["camera"] = {{"points", {{10, 10, 50}, {10, 10, 50}}}, {"speed_mps", 5}};
             }),
             StartsWith("s.json: /camera/points: needs at least 2 distinct points"));
  CHECK_THAT(error_with([](json& d) {
               d["camera"] = {{"points", {{-1e300, 10, 50}, {1e300, 10, 50}}}, {"speed_mps", 5}};
             }),
             StartsWith("s.json: /camera/points/0/0: must be in [-1e10, 1e10] m"));
  CHECK_THAT(error_with([](json& d) {
               d["camera"]["periodic_cut"] = {{"every_s", 1e-9}, {"jump_ahead_m", 50}};
             }),
             StartsWith("s.json: /camera/periodic_cut/every_s: must be >= 0.01"));
}

TEST_CASE("a road camera and traffic need the world's road", "[scenario]") {
  using Catch::Matchers::StartsWith;
  CHECK_THAT(error_with([](json& d) {
               d["world"]["road"]["enabled"] = false;
               d["receivers"].erase("traffic");
             }),
             StartsWith("s.json: /camera/type: \"road\" needs the world's road"));
  CHECK_THAT(error_with([](json& d) {
               d["world"]["road"]["enabled"] = false;
               d["camera"] = {{"points", {{10, 10, 50}, {100, 100, 50}}}, {"speed_mps", 5}};
             }),
             StartsWith("s.json: /receivers/traffic: needs the world's road"));
}

TEST_CASE("a road start beyond the end of the road is an input error", "[scenario][world]") {
  json d = small_scenario();
  d["camera"]["start_arc_length_m"] = 1e9;
  const ambisim::Scenario s = ambisim::parse_scenario(d, "s.json");
  const ambisim::World world(s.world);
  CHECK_THROWS_WITH(ambisim::check_scenario_world(s, world),
                    Catch::Matchers::StartsWith(
                        "s.json: /camera/start_arc_length_m: is beyond the end of the road"));
  d["camera"]["start_arc_length_m"] = 10;
  CHECK_NOTHROW(ambisim::check_scenario_world(ambisim::parse_scenario(d, "s.json"), world));
}

TEST_CASE("a number too large for a double is invalid JSON, not a crash", "[scenario]") {
  const std::string tmp =
      (std::filesystem::temp_directory_path() / "ambisim_test_overflow.json").string();
  {
    std::ofstream out(tmp, std::ios::binary);
    out << R"({"world": {"seed": 1e999}})";
  }
  std::string message = "no error";
  try {
    (void)ambisim::load_scenario(tmp);
  } catch (const InputError& e) {
    message = e.what();
  }
  std::filesystem::remove(tmp);
  CHECK_THAT(message, Catch::Matchers::Contains("invalid JSON: number overflow"));
}

TEST_CASE("sweep files are parsed from memory and checked", "[scenario][sweep]") {
  const std::string file = std::string(AMBISIM_SOURCE_DIR) + "/scenarios/sweeps/x.json";
  const auto sweep_error = [&](const char* text) {
    try {
      (void)ambisim::parse_sweep(json::parse(text), file);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK(sweep_error(R"({"scenarios": ["../walk.json"], "planners": ["constant"]})") == "no error");
  CHECK_THAT(sweep_error(R"({"scenarios": ["../walk.json"], "planners": ["constant"],
                             "fps": [30, 5000], "duration_s": 3600})"),
             Catch::Matchers::Contains("/duration_s: with fps 5000 gives 18000000 frames"));
  CHECK_THAT(sweep_error(R"({"scenarios": ["nope.json"], "planners": ["constant"]})"),
             Catch::Matchers::Contains("/scenarios/0: no such file"));
  CHECK_THAT(sweep_error(R"({"scenarios": ["../walk.json"],
                             "planners": [{"name": "constant", "label": "../../x"}]})"),
             Catch::Matchers::Contains("/planners/0/label: must be 1..100 characters"));
}

TEST_CASE("fuzz finding: a scenario path too long for the file system", "[scenario][sweep]") {
  // fuzz_sweep: std::filesystem::is_regular_file threw filesystem_error (ENAMETOOLONG) out of
  // parse_sweep, which the CLI reported as an internal error (exit 1).
  const std::string file = std::string(AMBISIM_SOURCE_DIR) + "/scenarios/sweeps/x.json";
  json doc = json::parse(R"({"planners": ["constant"]})");
  doc["scenarios"] = {std::string(600, '[') + ".json"};
  std::string message = "no error";
  try {
    (void)ambisim::parse_sweep(doc, file);
  } catch (const InputError& e) {
    message = e.what();
  }
  CHECK_THAT(message, Catch::Matchers::Contains("/scenarios/0: no such file"));
}
