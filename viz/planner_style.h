#pragma once
// One look per planner in every chart: a colour and a marker that no other planner in the chart
// shares, fixed by the planner's name so that a planner looks the same in every chart.
//
// The known planners have a fixed entry (known_planner_names()). Colours come from a palette of
// 21 colours chosen for lines and markers on white (every pair at least 12 CIEDE2000 apart, none
// within 20 of ambisim's red): 15 for the known planners, 4 spare for labels the table does not
// know, black for the oracle and a red that only ambisim uses. `ambisim`, the project's planner,
// is drawn thicker, with larger markers, on top of the others; the `oracle` (the representation's
// ceiling, not a planner a game can run) as a dashed black reference line.
//
// Labels the table does not know take, in sorted order, the next combination nobody in the chart
// holds: first a spare colour or the colour of a known planner absent from the chart (with its
// marker), then a palette colour with a marker that colour does not have yet. Their looks thus
// depend on the set of labels charted together (every chart of one sweep charts the same set).
#include <array>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace ambisim {

struct PlannerStyle {
  std::array<unsigned char, 3> rgb = {0, 0, 0};
  int marker = 4;      // vtkPlotPoints marker style: 1 cross, 2 plus, 3 square, 4 circle, 5 diamond
  int line_type = 1;   // vtkPen line type: 1 solid, 2 dash
  float width = 2.0f;  // line width (pixels)
  float marker_size = 9.0f;  // pixels
  bool emphasis = false;     // the project's planner: wider, larger, drawn last (on top)
  bool reference = false;    // the oracle: a reference line, not one of the planners compared
  friend bool operator==(const PlannerStyle&, const PlannerStyle&) = default;
};

// The planners with a fixed style, in table order.
const std::vector<std::string>& known_planner_names();

// The fixed style of a known planner; nullopt for any other label.
std::optional<PlannerStyle> known_planner_style(std::string_view name);

// The k-th marker after `marker` in a fixed cycle of the five (k = 0: `marker` itself): for
// variants of one planner (another fps or budget) drawn in its colour.
int marker_variant(int marker, int k);

// Styles for every label charted together (duplicates ignored): no two labels share both colour
// and marker (up to 95 labels; past that, combinations repeat).
std::map<std::string, PlannerStyle> planner_styles(const std::vector<std::string>& labels);

}  // namespace ambisim
