// Strict JSON reading: every error names the file and the JSON path.
#include <catch2/catch.hpp>

#include "sim/base/json_reader.h"

using ambisim::InputError;
using ambisim::ObjectReader;
using ambisim::Range;
using nlohmann::json;

namespace {
std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}
}  // namespace

TEST_CASE("json reader returns values and defaults") {
  const json j = json::parse(R"({"a": 2.5, "n": 3, "s": "x", "v": [1, 2, 3], "o": {"b": true}})");
  ObjectReader r(j, "f.json", "");
  CHECK(r.number("a", Range::positive()) == 2.5);
  CHECK(r.integer("n", 0) == 3);
  CHECK(r.number("missing", 7.0) == 7.0);
  CHECK(r.string("s") == "x");
  CHECK(r.vec3("v").z == 3.0);
  auto o = r.object("o");
  CHECK(o.boolean("b", false));
  o.finish();
  r.finish();
}

TEST_CASE("json reader errors name file and path") {
  const json j = json::parse(R"({"camera": {"speed_mps": -3, "typo": 1}, "n": 1.5})");
  CHECK(error_of([&] {
          ObjectReader r(j, "motorway.json", "");
          r.object("camera").number("speed_mps", Range::positive());
        }) == "motorway.json: /camera/speed_mps: must be > 0, got -3");
  CHECK(error_of([&] {
          ObjectReader r(j, "m.json", "");
          auto c = r.object("camera");
          c.number("speed_mps", 1.0);
          c.finish();
        }) == "m.json: /camera/typo: unknown key; valid keys: speed_mps");
  CHECK(error_of([&] {
          ObjectReader r(j, "m.json", "");
          r.integer("n", 0);
        }) == "m.json: /n: must be an integer, got number 1.5");
  CHECK(error_of([&] {
          ObjectReader r(j, "m.json", "");
          r.choice("kind", "spline", {"road", "keyframes"});
        }) == "m.json: /kind: unknown value \"spline\"; valid: road, keyframes");
  CHECK(error_of([&] { ObjectReader r(json::array(), "m.json", ""); }) ==
        "m.json: /: must be an object, got array");
}

TEST_CASE("json file loading reports empty, missing and malformed files") {
  CHECK(error_of([] { ambisim::load_json_file("/nonexistent/x.json"); }) ==
        "/nonexistent/x.json: no such file");
  CHECK(error_of([] { ambisim::load_json_file("/tmp"); }) ==
        "/tmp: is a directory, not a JSON file");
}
