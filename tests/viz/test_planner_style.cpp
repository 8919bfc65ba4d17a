// One look per planner: no two planners charted together share colour and marker, the known
// planners keep a fixed look, ambisim stands out, the colours stay apart on white.
#include <algorithm>
#include <catch2/catch.hpp>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "policies/registry/presets.h"
#include "policies/registry/registry.h"
#include "sim/colour/ciede2000.h"
#include "sim/colour/cielab.h"
#include "viz/planner_style.h"

using ambisim::PlannerStyle;

namespace {

// Every label's (colour, marker) is its own.
void check_no_two_alike(const std::vector<std::string>& labels) {
  const auto styles = ambisim::planner_styles(labels);
  REQUIRE(styles.size() == std::set<std::string>(labels.begin(), labels.end()).size());
  std::set<std::pair<std::array<unsigned char, 3>, int>> seen;
  for (const auto& [label, s] : styles) {
    INFO(label);
    CHECK(seen.insert({s.rgb, s.marker}).second);
    CHECK(s.marker >= 1);
    CHECK(s.marker <= 5);
  }
}

ambisim::Lab lab_of(const std::array<unsigned char, 3>& rgb) {
  const auto lin = [](unsigned char c) { return ambisim::srgb_decode(c / 255.0); };
  return ambisim::linear_srgb_to_lab({lin(rgb[0]), lin(rgb[1]), lin(rgb[2])});
}

std::vector<std::string> synthetic(int n) {
  std::vector<std::string> out;
  for (int k = 1; k <= n; ++k) out.push_back("planner_" + std::to_string(k));
  return out;
}

}  // namespace

TEST_CASE("every known planner has a fixed style of its own", "[viz][style]") {
  const auto& known = ambisim::known_planner_names();
  for (const char* name : {"oracle", "constant", "hemisphere", "nearest", "per_object", "grid",
                           "cascades", "baked", "baked_tod", "relit", "octree", "octree+vp",
                           "shgraph", "shgraph+vp", "shgraph+route", "shgraph2d", "ambisim"}) {
    INFO(name);
    CHECK(std::find(known.begin(), known.end(), name) != known.end());
    REQUIRE(ambisim::known_planner_style(name).has_value());
    // The same look whoever else is charted.
    CHECK(ambisim::planner_styles({name}).at(name) == *ambisim::known_planner_style(name));
    CHECK(ambisim::planner_styles({"zz_new", name, "aa_new"}).at(name) ==
          *ambisim::known_planner_style(name));
  }
  CHECK_FALSE(ambisim::known_planner_style("no_such_planner").has_value());
  check_no_two_alike(known);
  // Every colour of the table is its own (markers only separate unknown labels).
  std::set<std::array<unsigned char, 3>> colours;
  for (const auto& n : known) CHECK(colours.insert(ambisim::known_planner_style(n)->rgb).second);
}

TEST_CASE("ambisim stands out and the oracle is a reference", "[viz][style]") {
  const auto styles = ambisim::planner_styles(ambisim::known_planner_names());
  const PlannerStyle& a = styles.at("ambisim");
  const PlannerStyle& o = styles.at("oracle");
  CHECK(a.emphasis);
  CHECK_FALSE(a.reference);
  CHECK(o.reference);
  CHECK_FALSE(o.emphasis);
  CHECK(o.line_type != 1);  // dashed
  CHECK(o.rgb == std::array<unsigned char, 3>{0, 0, 0});
  for (const auto& [label, s] : styles) {
    if (label == "ambisim") continue;
    INFO(label);
    CHECK_FALSE(s.emphasis);
    CHECK(a.width > s.width);
    CHECK(a.marker_size > s.marker_size);
    CHECK(s.rgb != a.rgb);
    CHECK(ambisim::ciede2000(lab_of(s.rgb), lab_of(a.rgb)) >= 20.0);
    if (label != "oracle") CHECK_FALSE(s.reference);
  }
}

TEST_CASE("unknown labels take free combinations: no two alike in a 20-planner sweep",
          "[viz][style]") {
  check_no_two_alike(synthetic(20));
  // With every known planner too, and up to every combination of the palette.
  auto both = synthetic(20);
  for (const auto& n : ambisim::known_planner_names()) both.push_back(n);
  check_no_two_alike(both);
  check_no_two_alike(synthetic(95));
  // A 13-planner sweep plus new planners: the new ones get colours nobody in it has.
  std::vector<std::string> sweep = {
      "oracle",    "constant", "hemisphere", "nearest",       "per_object", "grid",   "octree",
      "octree+vp", "shgraph",  "shgraph+vp", "shgraph+route", "shgraph2d",  "ambisim"};
  const auto before = ambisim::planner_styles(sweep);
  for (const auto& n : synthetic(6)) sweep.push_back(n);
  const auto styles = ambisim::planner_styles(sweep);
  std::set<std::array<unsigned char, 3>> colours;
  for (const auto& [label, s] : styles) CHECK(colours.insert(s.rgb).second);
  // Deterministic: the order of the labels does not matter.
  std::reverse(sweep.begin(), sweep.end());
  CHECK(ambisim::planner_styles(sweep) == styles);
  for (const auto& [label, s] : before) CHECK(styles.at(label) == s);
}

TEST_CASE("planner colours stay apart and readable on white", "[viz][style]") {
  // Every colour a chart of known and new planners can use (the palette, black, ambisim's red).
  auto labels = synthetic(95);
  for (const auto& n : ambisim::known_planner_names()) labels.push_back(n);
  std::set<std::array<unsigned char, 3>> colours;
  for (const auto& [label, s] : ambisim::planner_styles(labels)) colours.insert(s.rgb);
  CHECK(colours.size() == 21);
  const std::vector<std::array<unsigned char, 3>> all(colours.begin(), colours.end());
  double smallest = 1e9;
  for (std::size_t i = 0; i < all.size(); ++i) {
    CHECK(ambisim::ciede2000(lab_of(all[i]), {100.0, 0.0, 0.0}) >= 25.0);
    for (std::size_t j = i + 1; j < all.size(); ++j) {
      smallest = std::min(smallest, ambisim::ciede2000(lab_of(all[i]), lab_of(all[j])));
    }
  }
  CHECK(smallest >= 12.0);
}

TEST_CASE("marker variants cycle through the five markers", "[viz][style]") {
  std::set<int> seen;
  for (int k = 0; k < 5; ++k) seen.insert(ambisim::marker_variant(3, k));
  CHECK(seen.size() == 5);
  CHECK(ambisim::marker_variant(3, 0) == 3);
  CHECK(ambisim::marker_variant(3, 5) == 3);
}

TEST_CASE("every registered planner and its preset labels: no two alike in one chart",
          "[viz][style]") {
  // What a sweep over the whole registry charts: each planner by name and, for every preset,
  // NAME_PRESET (sweep.cpp's label for a preset run), all at once.
  std::vector<std::string> labels;
  for (const auto& info : ambisim::planner_catalogue()) {
    labels.push_back(info.name);
    for (const auto& preset : ambisim::preset_names()) labels.push_back(info.name + "_" + preset);
  }
  REQUIRE(labels.size() > ambisim::planner_catalogue().size());
  check_no_two_alike(labels);
  // Every registered planner has a fixed look, which a preset label never takes over.
  const auto styles = ambisim::planner_styles(labels);
  for (const auto& info : ambisim::planner_catalogue()) {
    INFO(info.name);
    REQUIRE(ambisim::known_planner_style(info.name).has_value());
    CHECK(styles.at(info.name) == *ambisim::known_planner_style(info.name));
  }
  // Deterministic: the same labels in another order give the same looks.
  auto reversed = labels;
  std::reverse(reversed.begin(), reversed.end());
  CHECK(ambisim::planner_styles(reversed) == styles);
  // Only ambisim is emphasised; its tuned label is drawn like any other planner.
  for (const auto& [label, s] : styles) {
    INFO(label);
    CHECK(s.emphasis == (label == "ambisim"));
  }
}
