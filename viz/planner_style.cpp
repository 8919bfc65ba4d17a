#include "viz/planner_style.h"

#include <algorithm>
#include <set>
#include <utility>

namespace ambisim {
namespace {

// Marker styles in the order unknown labels try them: the filled shapes read best.
constexpr int kMarkers[] = {4, 3, 5, 1, 2};
constexpr int kMarkerCount = 5;

struct PaletteColour {
  unsigned char rgb[3];
  int marker;  // its marker in the table (and the first one an unknown label tries)
};

// 19 colours for lines and markers on white, chosen greedily for the largest smallest CIEDE2000
// difference among themselves, to black, to white, to ambisim's red and to the grey of the
// Pareto front (smallest pairwise difference 12.8; tests/viz/test_planner_style.cpp checks it).
// The first 15 belong to the known planners below; the last 4 are spare.
constexpr PaletteColour kPalette[] = {
    {{189, 183, 107}, 5},  // 0 khaki: constant
    {{128, 128, 0}, 4},    // 1 olive: hemisphere
    {{245, 130, 49}, 3},   // 2 orange: nearest
    {{169, 142, 224}, 5},  // 3 lavender: per_object
    {{154, 99, 36}, 1},    // 4 brown: grid
    {{60, 180, 75}, 4},    // 5 green: cascades
    {{27, 94, 32}, 3},     // 6 dark green: baked
    {{154, 205, 50}, 2},   // 7 yellow-green: baked_tod
    {{70, 153, 144}, 1},   // 8 teal: relit
    {{142, 69, 133}, 3},   // 9 plum: octree
    {{240, 50, 230}, 4},   // 10 magenta: octree+vp
    {{70, 130, 180}, 4},   // 11 steel blue: shgraph
    {{0, 0, 117}, 3},      // 12 navy: shgraph+vp
    {{66, 212, 244}, 5},   // 13 cyan: shgraph+route
    {{63, 81, 181}, 1},    // 14 indigo: shgraph2d
    {{255, 176, 0}, 4},    // 15 amber (spare)
    {{61, 220, 151}, 3},   // 16 mint (spare)
    {{247, 143, 179}, 4},  // 17 pink (spare)
    {{111, 168, 220}, 5},  // 18 sky blue (spare)
};
constexpr int kPaletteSize = 19;
constexpr int kFirstSpare = 15;

// The known planners and their palette colour; -1: oracle (black), -2: ambisim (red).
constexpr std::pair<const char*, int> kKnown[] = {
    {"oracle", -1},    {"constant", 0},    {"hemisphere", 1},     {"nearest", 2},
    {"per_object", 3}, {"grid", 4},        {"cascades", 5},       {"baked", 6},
    {"baked_tod", 7},  {"relit", 8},       {"octree", 9},         {"octree+vp", 10},
    {"shgraph", 11},   {"shgraph+vp", 12}, {"shgraph+route", 13}, {"shgraph2d", 14},
    {"ambisim", -2}};

PlannerStyle palette_style(int colour, int marker) {
  PlannerStyle s;
  std::copy(kPalette[colour].rgb, kPalette[colour].rgb + 3, s.rgb.begin());
  s.marker = marker;
  return s;
}

PlannerStyle known_style(int colour) {
  if (colour >= 0) return palette_style(colour, kPalette[colour].marker);
  PlannerStyle s;
  if (colour == -1) {  // oracle: the reference
    s.rgb = {0, 0, 0};
    s.marker = 3;
    s.line_type = 2;
    s.marker_size = 7.0f;
    s.reference = true;
  } else {  // ambisim: a red nobody else has, wider, larger, on top
    s.rgb = {230, 0, 46};
    s.marker = 4;
    s.width = 4.0f;
    s.marker_size = 14.0f;
    s.emphasis = true;
  }
  return s;
}

int known_colour(std::string_view name) {
  for (const auto& [n, c] : kKnown) {
    if (name == n) return c;
  }
  return -3;
}

int rotated_marker(int colour, int pass) { return marker_variant(kPalette[colour].marker, pass); }

}  // namespace

int marker_variant(int marker, int k) {
  const auto first = std::find(kMarkers, kMarkers + kMarkerCount, marker) - kMarkers;
  return kMarkers[(static_cast<int>(first) + std::max(0, k)) % kMarkerCount];
}

const std::vector<std::string>& known_planner_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const auto& [n, c] : kKnown) out.emplace_back(n);
    return out;
  }();
  return names;
}

std::optional<PlannerStyle> known_planner_style(std::string_view name) {
  const int c = known_colour(name);
  if (c == -3) return std::nullopt;
  return known_style(c);
}

std::map<std::string, PlannerStyle> planner_styles(const std::vector<std::string>& labels) {
  const std::set<std::string> sorted(labels.begin(), labels.end());
  std::map<std::string, PlannerStyle> out;
  std::set<std::pair<int, int>> taken;  // (palette colour, marker)
  std::set<int> colours;
  for (const auto& l : sorted) {
    const int c = known_colour(l);
    if (c == -3) continue;
    out[l] = known_style(c);
    if (c >= 0) {
      taken.insert({c, kPalette[c].marker});
      colours.insert(c);
    }
  }
  // Unknown labels: spare colours first, then the colours of absent known planners, each with
  // its own marker; then every colour with the markers it does not have yet.
  std::vector<std::pair<int, int>> candidates;
  for (int pass = 0; pass < kMarkerCount; ++pass) {
    for (int k = 0; k < kPaletteSize; ++k) {
      const int c = (kFirstSpare + k) % kPaletteSize;
      if (pass == 0 && colours.contains(c)) continue;
      candidates.emplace_back(c, rotated_marker(c, pass));
    }
  }
  std::size_t next = 0, reused = 0;
  for (const auto& l : sorted) {
    if (out.contains(l)) continue;
    while (next < candidates.size() && taken.contains(candidates[next])) ++next;
    std::pair<int, int> pick;
    if (next < candidates.size()) {
      pick = candidates[next++];
    } else {  // every combination is taken: repeat them in order
      const int c = static_cast<int>(reused % kPaletteSize);
      pick = {c, rotated_marker(c, static_cast<int>(reused / kPaletteSize) % kMarkerCount)};
      ++reused;
    }
    taken.insert(pick);
    out[l] = palette_style(pick.first, pick.second);
  }
  return out;
}

}  // namespace ambisim
