#pragma once
// `ambisim plot`: PNG charts of a sweep directory (summary.csv, timing.csv, runs/*/result.json),
// drawn with VTK's 2-D charts offscreen. One chart set per scenario, written to DIR/charts/:
//   <scenario>_accuracy_cost.png   ΔE00 p95 against the costs: capture budget (faces/s, a line
//                                  per planner), the planner's CPU time per frame and its peak
//                                  memory (a point per budget), each with its Pareto front
//                                  (lower cost and lower error; the oracle left out);
//   <scenario>_speed.png           ΔE00 p95 and pops per minute against camera speed;
//   <scenario>_coverage_budget.png coverage against capture budget;
//   <scenario>_seeds.png           box plots across seeds (min, quartiles, median, max, and
//                                  every seed as a dot) of viewed and uniform p95 and pops per
//                                  planner, at the nominal speed and budget; only when the sweep
//                                  has several seeds.
// With several seeds, every other chart plots the mean over the seeds.
//   <scenario>_light.png           (light that changes) viewed and uniform mean error over
//                                  the time of day, every planner (see light_time_axis);
//   <run>_series.png               one run's time series (error, pops, live probes, coverage):
//                                  the first run of each scenario, or the run chosen.
// Every planner keeps one style (colour, marker) in every chart of the sweep
// (viz/planner_style.h); a figure whose panels show the same planners has one legend, outside
// the plots. Cost axes are logarithmic where the values span 8x or more.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sim/base/output_file.h"

namespace ambisim {

struct PlotOptions {
  std::string run_id;  // time series of this run only; empty: the first run of each scenario
  Overwrite overwrite = Overwrite::refuse;
  int width = 1200;
  int height = 800;
};

// The light chart (<scenario>_light.png, drawn when a scenario's world lights itself
// differently over time: a sun on a path, clouds, lamps or fog) plots viewed and uniform mean
// error against time for every planner, at the nominal speed and the budget nearest 1 face
// per frame, averaged over the seeds. Whether a run's result.json document changes its light:
bool scenario_light_changes(const nlohmann::json& result);
// Its x axis: x = start + scale x t, the local time of day in hours for a sun on the solar path
// (start, time_scale), else the run's time in seconds.
struct TimeAxis {
  double start = 0.0, scale = 1.0;
  std::string label = "time (s)";
};
TimeAxis light_time_axis(const nlohmann::json& result);

// Writes the charts; returns the paths written. Throws InputError (naming the file) for a
// missing directory or summary.csv, missing columns, an unknown run id, or an output that
// exists without Overwrite::allow (checked before anything is written).
std::vector<std::string> write_sweep_charts(const std::string& sweep_dir,
                                            const PlotOptions& options);

// One line of a chart (exposed for tests).
struct ChartSeries {
  std::string name;
  std::vector<double> x, y;  // NaN points are dropped
  unsigned char rgb[3] = {0, 0, 0};
  unsigned char alpha = 255;
  float width = 2.5f;
  int line_type = 1;  // vtkPen line type: 0 none, 1 solid, 2 dash, 3 dot, 4 dash-dot
  int marker = 4;     // vtkPlotPoints marker style: 0 none, 1 cross, 2 plus, 3 square, 4 circle,
                      // 5 diamond
  float marker_size = 9.0f;
  bool on_top = false;     // drawn after every other series (the project's planner)
  bool reference = false;  // a reference, not a contender: left out of the Pareto front
};

struct ChartPanel {
  std::string title, x_label, y_label;
  std::vector<ChartSeries> series;
  bool log_x = false;
  std::vector<double> log_x_ticks;  // a log x axis's ticks (e.g. the budgets swept), when they
                                    // fit; empty or crowded: 1-2-5 per decade or sparser
  bool log_y = false;               // log scale (points with y <= 0 dropped; y_from_zero ignored)
  bool y_from_zero = true;
  bool stagger_widths = false;  // earlier series drawn wider (equal results stay visible)
  bool legend = true;           // an inline legend (top right; the y axis makes room for it)
  // Category axis: one label per x = 0, 1, 2, ... (box plots); empty: a numeric axis.
  std::vector<std::string> x_tick_labels;
};

// The axis ranges a panel is drawn with (data units, also for log axes): the data with a margin
// of 4% of the span (of the decades when log) on each side, y from zero when `y_from_zero` (and
// no data below); category axes from -0.6 to n - 0.4; the y axis grown by `legend_room`, the
// fraction of the plot an inline legend takes at the top (0 when the legend is outside).
struct AxisRanges {
  double x[2], y[2];
};
AxisRanges panel_ranges(const ChartPanel& p, double legend_room = 0.0);

// Renders panels (row-major, `columns` per row) under a title into one PNG. Axes fit the data
// with a small margin. `shared_legend`: one legend for the figure instead of one per panel (for
// panels that draw the same series alike): the legend of the panel listing the most series,
// outside every plot, in the first empty cell of the grid or else right of the panels.
void write_chart_png(const std::string& title, const std::vector<ChartPanel>& panels, int columns,
                     const std::string& path, Overwrite overwrite, int width, int height,
                     bool shared_legend = false);

}  // namespace ambisim
