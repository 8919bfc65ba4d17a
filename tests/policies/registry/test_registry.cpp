// Registry and parameter handling: names, defaults, JSON and --set parsing, error texts.
#include <catch2/catch.hpp>

#include <string>

#include "policies/core/planner_params.h"
#include "policies/registry/presets.h"
#include "policies/registry/registry.h"
#include "sim/base/input_error.h"

using namespace ambisim;

namespace {

// The message of the InputError `f` throws ("" if none).
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

const std::vector<std::string> kExpectedPlanners = {
    "oracle",   "constant",   "hemisphere",    "nearest",   "per_object", "grid",
    "cascades", "relit",      "baked",         "baked_tod", "octree",     "octree+vp",
    "shgraph",  "shgraph+vp", "shgraph+route", "shgraph2d", "ambisim"};

std::string expected_list() {
  std::string s;
  for (const auto& n : kExpectedPlanners) s += (s.empty() ? "" : ", ") + n;
  return s;
}

}  // namespace

TEST_CASE("the catalogue lists every planner and each builds with defaults", "[policies]") {
  const auto& all = planner_catalogue();
  std::vector<std::string> names;
  for (const auto& info : all) names.push_back(info.name);
  // Every planner the product promises (SPEC section 4), in catalogue order.
  CHECK(names == kExpectedPlanners);
  for (const auto& info : all) {
    INFO(info.name);
    CHECK_FALSE(info.description.empty());
    const auto p = make_planner(info.name);
    REQUIRE(p);
    CHECK(p->name() == info.name);
    // params() echoes every declared parameter with its default.
    const nlohmann::json echoed = p->params();
    CHECK(echoed.size() == info.params.size());
    for (const auto& s : info.params) CHECK(echoed.at(s.name) == s.default_value);
  }
  CHECK(make_planner("oracle")->ignores_budget());
  CHECK_FALSE(make_planner("nearest")->ignores_budget());
}

TEST_CASE("nearest declares its parameters with the documented defaults", "[policies]") {
  const nlohmann::json p = make_planner("nearest")->params();
  CHECK(p == nlohmann::json{{"spacing_m", 8.0},
                            {"max_probes", 256},
                            {"lifetime_s", 60.0},
                            {"blend_s", 0.5},
                            {"predict", false}});
}

TEST_CASE("an unknown planner name lists the valid names", "[policies]") {
  const std::string msg = error_of([] { make_planner("octopus"); });
  CHECK(msg == "<input>: unknown planner \"octopus\"; valid planners: " + expected_list());
  const std::string at = error_of([] { find_planner("x", "sweep.json", "/planners/2/name"); });
  CHECK(at ==
        "sweep.json: /planners/2/name: unknown planner \"x\"; valid planners: " + expected_list());
}

TEST_CASE("an unknown parameter lists the valid ones with their defaults", "[policies]") {
  const std::string cli = error_of([] { planner_params_from_cli("nearest", {"spcing_m=4"}); });
  CHECK(cli ==
        "--set spcing_m=4: unknown parameter \"spcing_m\" for planner \"nearest\"; valid "
        "parameters (defaults): spacing_m=8, max_probes=256, lifetime_s=60, blend_s=0.5, "
        "predict=false");
  const nlohmann::json j = {{"blend_s", 1.0}, {"max_probe", 3}};
  const std::string json =
      error_of([&] { planner_params_from_json("nearest", j, "run.json", "/planner/params"); });
  CHECK(contains(json, "run.json: /planner/params/max_probe: unknown parameter \"max_probe\""));
  CHECK(contains(json, "max_probes=256"));
  const std::string none = error_of([] { planner_params_from_cli("oracle", {"k=1"}); });
  CHECK(none == "--set k=1: unknown parameter \"k\": planner \"oracle\" has no parameters");
}

TEST_CASE("CLI --set values are parsed by their look and validated", "[policies]") {
  const auto p = planner_params_from_cli(
      "nearest", {"spacing_m=4", "max_probes=12", "blend_s=1.5e-1", "predict=true"});
  CHECK(p.number("spacing_m") == 4.0);
  CHECK(p.integer("max_probes") == 12);
  CHECK(p.number("max_probes") == 12.0);
  CHECK(p.number("blend_s") == Approx(0.15).margin(1e-15));
  CHECK(p.boolean("predict"));
  CHECK(p.number("lifetime_s") == 60.0);  // default
  CHECK(p.is_set("spacing_m"));
  CHECK_FALSE(p.is_set("lifetime_s"));
  // A later --set overrides; the planner echoes the effective values.
  auto q = p;
  q.set_cli("spacing_m=2.5");
  const auto planner = make_planner("nearest", q);
  CHECK(planner->params().at("spacing_m") == 2.5);
  CHECK(planner->params().at("max_probes") == 12);
  CHECK(planner->params().at("predict") == true);

  CHECK(parse_cli_value("12") == nlohmann::json(12));
  CHECK(parse_cli_value("-0.5") == nlohmann::json(-0.5));
  CHECK(parse_cli_value("false") == nlohmann::json(false));
  CHECK(parse_cli_value("8m") == nlohmann::json("8m"));
  CHECK(parse_cli_value("inf") == nlohmann::json("inf"));
  CHECK(parse_cli_value("") == nlohmann::json(""));
}

TEST_CASE("bad values name the parameter and the allowed range", "[policies]") {
  CHECK(error_of([] { planner_params_from_cli("nearest", {"spacing_m=-3"}); }) ==
        "--set spacing_m=-3: parameter \"spacing_m\" of planner \"nearest\" must be a number > 0, "
        "got -3");
  CHECK(error_of([] { planner_params_from_cli("nearest", {"spacing_m=abc"}); }) ==
        "--set spacing_m=abc: parameter \"spacing_m\" of planner \"nearest\" must be a number > "
        "0, got \"abc\"");
  CHECK(error_of([] { planner_params_from_cli("nearest", {"max_probes=2.5"}); }) ==
        "--set max_probes=2.5: parameter \"max_probes\" of planner \"nearest\" must be an "
        "integer in [1, 1000000000], got 2.5");
  CHECK(error_of([] { planner_params_from_cli("nearest", {"max_probes=0"}); }) ==
        "--set max_probes=0: parameter \"max_probes\" of planner \"nearest\" must be an integer "
        "in [1, 1000000000], got 0");
  CHECK(error_of([] { planner_params_from_cli("nearest", {"predict=1"}); }) ==
        "--set predict=1: parameter \"predict\" of planner \"nearest\" must be true or false, "
        "got 1");
  CHECK(error_of([] { planner_params_from_cli("nearest", {"predict"}); }) ==
        "--set predict: expected key=value");
  CHECK(error_of([] { planner_params_from_cli("constant", {"colour_r=-0.1"}); }) ==
        "--set colour_r=-0.1: parameter \"colour_r\" of planner \"constant\" must be a number >= "
        "0, got -0.1");
  // From JSON: the file and JSON path (RFC 6901 escaped) lead the message.
  const nlohmann::json j = {{"blend_s", "slow"}};
  CHECK(error_of([&] { planner_params_from_json("nearest", j, "s.json", "/runs/0/params"); }) ==
        "s.json: /runs/0/params/blend_s: parameter \"blend_s\" of planner \"nearest\" must be a "
        "number >= 0, got \"slow\"");
  CHECK(error_of([] {
          planner_params_from_json("nearest", nlohmann::json::array(), "s.json", "/p");
        }) == "s.json: /p: must be an object, got array");
}

TEST_CASE("JSON parameters are validated and bound to the planner", "[policies]") {
  const nlohmann::json j = {{"spacing_m", 3}, {"lifetime_s", 10.5}};
  const auto p = planner_params_from_json("nearest", j, "s.json", "");
  CHECK(p.number("spacing_m") == 3.0);
  CHECK(p.to_json().at("spacing_m") == 3.0);  // canonical double, even from a JSON integer
  CHECK(p.to_json().at("max_probes") == 256);
  CHECK(make_planner("nearest", p)->params().at("lifetime_s") == 10.5);
  // Values bound for one planner are re-checked against another's specs, keeping their origin.
  CHECK(error_of([&] { make_planner("constant", p); }) ==
        "s.json: /lifetime_s: unknown parameter \"lifetime_s\" for planner \"constant\"; valid "
        "parameters (defaults): colour_r=0.5, colour_g=0.5, colour_b=0.5");
}

TEST_CASE("choice parameters accept only their choices, also from --set", "[policies]") {
  const std::vector<ParamSpec> specs = {
      choice_param("lookup", "trilinear", {"trilinear", "octant", "2"}, "lookup scheme"),
      number_param("fraction", 0.25, Range::closed(0.0, 1.0), "a fraction")};
  auto p = PlannerParams::from_cli("demo", specs, {"lookup=2"});
  CHECK(p.choice("lookup") == "2");  // a choice stays a string even if it looks numeric
  p.set_cli("lookup=octant");
  CHECK(p.choice("lookup") == "octant");
  CHECK(error_of([&] { p.set_cli("lookup=nearest"); }) ==
        "--set lookup=nearest: parameter \"lookup\" of planner \"demo\" must be one of "
        "trilinear, octant, 2, got \"nearest\"");
  CHECK(error_of([&] { p.set_cli("fraction=1.5"); }) ==
        "--set fraction=1.5: parameter \"fraction\" of planner \"demo\" must be a number in [0, "
        "1], got 1.5");
  CHECK_THROWS_AS(p.number("lookup"), std::logic_error);   // wrong type: a programming error
  CHECK_THROWS_AS(p.number("missing"), std::logic_error);  // undeclared
}

TEST_CASE("the catalogue renders as text with every parameter", "[policies]") {
  const std::string text = format_catalogue();
  CHECK(contains(text, "oracle: "));
  CHECK(contains(text, "    (no parameters)\n"));
  CHECK(contains(text, "nearest: nearest finished probe"));
  for (const auto& info : planner_catalogue()) {
    for (const auto& s : info.params) {
      INFO(s.name);
      CHECK(contains(text, "    " + s.name + " "));
    }
  }
  CHECK(contains(text, "    spacing_m   number   8      > 0              request a capture"));
  const nlohmann::json j = catalogue_json();
  REQUIRE(j.size() == kExpectedPlanners.size());
  CHECK(j[3]["name"] == "nearest");
  CHECK(j[3]["params"][1]["allowed"] == "[1, 1000000000]");
}

TEST_CASE("every planner has a tuned preset, and explicit values win over it", "[policies]") {
  CHECK(preset_names() == std::vector<std::string>{"tuned"});
  for (const auto& info : planner_catalogue()) {
    INFO(info.name);
    const nlohmann::json& tuned = preset_params(info.name, "tuned");
    REQUIRE(tuned.is_object());
    // Every value is a valid parameter of the planner, and the planner builds with them.
    const PlannerParams p = planner_params_from_json(info.name, nlohmann::json::object(), "t.json",
                                                     "/params", "tuned", "/preset");
    for (const auto& [k, v] : tuned.items()) {
      CHECK(p.is_set(k));
      CHECK(p.to_json().at(k) == v);
    }
    CHECK(make_planner(info.name, p) != nullptr);
    // An explicit value overrides the preset's.
    if (!info.params.empty()) {
      const ParamSpec& first = info.params.front();
      const PlannerParams q =
          planner_params_from_json(info.name, nlohmann::json{{first.name, first.default_value}},
                                   "t.json", "/params", "tuned", "/preset");
      CHECK(q.to_json().at(first.name) == first.default_value);
    }
  }
  try {
    planner_params_from_cli("nearest", {}, "tunde");
    FAIL("an unknown preset was accepted");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("valid presets: tuned") != std::string::npos);
  }
  CHECK(format_catalogue().find("preset tuned: ") != std::string::npos);
}
