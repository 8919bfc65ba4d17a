#include "viz/charts.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
#include <set>
#include <tuple>

#include <vtkAxis.h>
#include <vtkBrush.h>
#include <vtkChartLegend.h>
#include <vtkChartMatrix.h>
#include <vtkChartXY.h>
#include <vtkContextScene.h>
#include <vtkContextView.h>
#include <vtkDoubleArray.h>
#include <vtkFloatArray.h>
#include <vtkNew.h>
#include <vtkPen.h>
#include <vtkPlot.h>
#include <vtkPlotPoints.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkStringArray.h>
#include <vtkTable.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkVector.h>
#include <nlohmann/json.hpp>

#include "sim/base/csv_table.h"
#include "sim/base/input_error.h"
#include "sim/base/json_reader.h"
#include "sim/base/statistics.h"
#include "viz/planner_style.h"
#include "viz/render_capture.h"

namespace fs = std::filesystem;

namespace ambisim {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Tableau 10, for the lines of one run's time series (quantities, not planners).
constexpr unsigned char kSeriesColours[][3] = {
    {31, 119, 180}, {255, 127, 14},  {44, 160, 44},   {214, 39, 40},  {148, 103, 189},
    {140, 86, 75},  {227, 119, 194}, {127, 127, 127}, {188, 189, 34}, {23, 190, 207}};

// Legends: font size and the size VTK will give them. VTK measures text only while painting;
// these match its default font (measured on the charts at 14 points): an entry is the font's
// height plus 5 pixels of padding, a character about half the font size wide.
constexpr int kLegendFont = 14;
constexpr int kLegendFontMin = 8;
constexpr float kLegendPadding = 5.0f;  // vtkChartLegend's default
constexpr float kLegendChar = 0.51f;    // mean character width per point of font size
constexpr float kLegendSymbol = 36.0f;  // symbol width, paddings and border

std::string fmt(double v) {
  char buf[32];
  if (std::fabs(v - std::round(v)) < 1e-9 && std::fabs(v) < 1e9) {
    std::snprintf(buf, sizeof buf, "%.0f", v);
  } else {
    std::snprintf(buf, sizeof buf, "%.3g", v);
  }
  return buf;
}

// One run of summary.csv with what the charts need.
// With several seeds per condition, a point is the mean over its seeds (per_seed keeps them).
struct RunPoint {
  std::string run, scenario, label;  // run: the first seed's run
  double faces_per_frame = kNaN, speed_scale = kNaN, fps = kNaN, faces_per_s = kNaN;
  double speed = kNaN;  // m/s, or the speed scale when the scenario's speed is unknown
  double de_p95 = kNaN, pops_per_min = kNaN, coverage = kNaN, us_per_frame = kNaN;
  double max_bytes = kNaN;  // the planner's peak memory
  struct Seed {
    double viewed_p95, viewed_pops, uniform_p95, uniform_pops;
  };
  std::vector<Seed> per_seed;
  std::vector<std::string> seed_runs;  // every seed's run id
};

struct ScenarioInfo {
  std::string name;
  bool speed_known = false;  // speed in m/s (else: speed scale)
  std::vector<const RunPoint*> runs;
};

// The scenario's camera speed in m/s from a run's result.json document (already scaled by the
// run's speed_scale): "speed_mps", or the mean of a speed profile's breakpoints.
std::optional<double> document_speed(const nlohmann::json& result) {
  const auto* cam = &result;
  for (const char* key : {"scenario", "document", "camera"}) {
    if (!cam->is_object() || !cam->contains(key)) return std::nullopt;
    cam = &(*cam)[key];
  }
  if (cam->contains("speed_mps") && (*cam)["speed_mps"].is_number()) {
    return (*cam)["speed_mps"].get<double>();
  }
  if (cam->contains("speed_profile") && (*cam)["speed_profile"].is_array()) {
    double sum = 0.0;
    int n = 0;
    for (const auto& p : (*cam)["speed_profile"]) {
      if (p.is_object() && p.contains("speed_mps") && p["speed_mps"].is_number()) {
        sum += p["speed_mps"].get<double>();
        ++n;
      }
    }
    if (n > 0) return sum / n;
  }
  return std::nullopt;
}

vtkSmartPointer<vtkTable> make_table(const ChartSeries& s, bool log_x, bool log_y) {
  vtkNew<vtkFloatArray> xs, ys;
  xs->SetName("x");
  ys->SetName(s.name.c_str());
  std::vector<std::pair<double, double>> pts;
  for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
    if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
    if ((log_x && s.x[i] <= 0.0) || (log_y && s.y[i] <= 0.0)) continue;
    pts.emplace_back(s.x[i], s.y[i]);
  }
  for (const auto& [x, y] : pts) {
    xs->InsertNextValue(static_cast<float>(x));
    ys->InsertNextValue(static_cast<float>(y));
  }
  auto table = vtkSmartPointer<vtkTable>::New();
  table->AddColumn(xs);
  table->AddColumn(ys);
  return table;
}

void style_axis(vtkAxis* axis, const std::string& title) {
  axis->SetTitle(title);
  axis->GetTitleProperties()->SetFontSize(17);
  axis->GetTitleProperties()->BoldOff();
  axis->GetLabelProperties()->SetFontSize(14);
  axis->GetGridPen()->SetColor(225, 225, 225, 255);
}

// Data range of a panel's finite points (x > 0 when log_x, y > 0 when log_y).
bool data_range(const ChartPanel& p, double x[2], double y[2]) {
  x[0] = y[0] = std::numeric_limits<double>::infinity();
  x[1] = y[1] = -std::numeric_limits<double>::infinity();
  bool any = false;
  for (const auto& s : p.series) {
    for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i]) || (p.log_x && s.x[i] <= 0) ||
          (p.log_y && s.y[i] <= 0)) {
        continue;
      }
      x[0] = std::min(x[0], s.x[i]);
      x[1] = std::max(x[1], s.x[i]);
      y[0] = std::min(y[0], s.y[i]);
      y[1] = std::max(y[1], s.y[i]);
      any = true;
    }
  }
  return any;
}

// The series a legend lists: those with a name and a point to draw.
std::vector<std::string> legend_names(const ChartPanel& p) {
  std::vector<std::string> out;
  for (const auto& s : p.series) {
    if (!s.name.empty() && make_table(s, p.log_x, p.log_y)->GetNumberOfRows() > 0) {
      out.push_back(s.name);
    }
  }
  return out;
}

// Estimated legend box in pixels (width, height) for these entries at this font size.
vtkVector2f legend_size(const std::vector<std::string>& names, int font = kLegendFont) {
  std::size_t chars = 0;
  for (const auto& n : names) {
    // UTF-8: count code points, not bytes.
    std::size_t c = 0;
    for (unsigned char ch : n) c += (ch & 0xC0) != 0x80;
    chars = std::max(chars, c);
  }
  const auto f = static_cast<float>(font);
  return {kLegendSymbol + kLegendChar * f * static_cast<float>(chars),
          kLegendPadding + 1.0f + (f + kLegendPadding) * static_cast<float>(names.size())};
}

// Axis range with a small margin, `frac` of the span on each side (in decades when log).
void pad_range(double r[2], bool log, double frac) {
  if (log) {
    const double l0 = std::log10(r[0]), l1 = std::log10(r[1]);
    const double pad = l1 > l0 ? frac * (l1 - l0) : 0.1;
    r[0] = std::pow(10.0, l0 - pad);
    r[1] = std::pow(10.0, l1 + pad);
    return;
  }
  const double pad = r[1] > r[0] ? frac * (r[1] - r[0]) : std::max(0.5, 0.1 * std::fabs(r[0]));
  r[0] -= pad;
  r[1] += pad;
}

}  // namespace

AxisRanges panel_ranges(const ChartPanel& p, double legend_room) {
  AxisRanges r;
  double* xr = r.x;
  double* yr = r.y;
  if (!data_range(p, xr, yr)) {  // nothing to draw: a unit (or one-decade) range
    xr[0] = p.log_x ? 1.0 : 0.0;
    xr[1] = p.log_x ? 10.0 : 1.0;
    yr[0] = p.log_y ? 1.0 : 0.0;
    yr[1] = p.log_y ? 10.0 : 1.0;
  }
  if (!p.x_tick_labels.empty()) {
    xr[0] = -0.6;
    xr[1] = static_cast<double>(p.x_tick_labels.size()) - 0.4;
  } else {
    pad_range(xr, p.log_x, 0.04);
  }
  // y: the data with a small margin (from zero when asked), plus the inline legend's room.
  const double room = std::clamp(legend_room, 0.0, 0.6);
  if (p.log_y) {
    pad_range(yr, true, 0.04);
    const double l0 = std::log10(yr[0]), l1 = std::log10(yr[1]);
    yr[1] = std::pow(10.0, l0 + (l1 - l0) / (1.0 - room));
  } else {
    double y0 = p.y_from_zero ? std::min(0.0, yr[0]) : yr[0];
    double y1 = yr[1];
    if (y1 <= y0) y1 = y0 + 1.0;
    const double span = y1 - y0;
    if (!p.y_from_zero || yr[0] < 0.0) y0 -= 0.04 * span;
    y1 += 0.04 * span;
    yr[0] = y0;
    yr[1] = y0 + (y1 - y0) / (1.0 - room);
  }
  return r;
}

namespace {

// A tick label: short for big numbers (20k, 1.5M).
std::string tick_text(double v) {
  if (v >= 1e6) return fmt(v / 1e6) + "M";
  if (v >= 1e4) return fmt(v / 1e3) + "k";
  return fmt(v);
}

// Ticks of a log axis over [lo, hi] (data units), every label readable: at `preset` values
// when given and they do not crowd, else 1-2-5 per decade when there is room for them along
// the axis (`length` pixels), else 1-3, else decades (every decade, or every other one, ...).
// VTK's own log ticks leave the data's end unlabelled.
void set_log_ticks(vtkAxis* axis, double lo, double hi, float length, bool horizontal,
                   const std::vector<double>& preset) {
  const auto ticks_of = [&](const std::vector<double>& mantissas, int decade_step) {
    std::vector<double> out;
    for (int e = static_cast<int>(std::floor(std::log10(lo))) - 1;
         e <= static_cast<int>(std::ceil(std::log10(hi))); ++e) {
      if (e % decade_step != 0) continue;
      for (double m : mantissas) {
        const double v = m * std::pow(10.0, e);
        if (v >= lo * (1 - 1e-9) && v <= hi * (1 + 1e-9)) out.push_back(v);
      }
    }
    return out;
  };
  // Neighbouring labels must not touch: their distance along the axis against their size.
  const double decades = std::log10(hi) - std::log10(lo);
  const auto extent = [&](double v) {
    return horizontal ? 10.0 + 8.0 * static_cast<double>(tick_text(v).size()) : 24.0;
  };
  const auto fits = [&](const std::vector<double>& t) {
    for (std::size_t i = 1; i < t.size(); ++i) {
      const double gap = length * (std::log10(t[i]) - std::log10(t[i - 1])) / decades;
      if (gap < 0.5 * (extent(t[i]) + extent(t[i - 1]))) return false;
    }
    return true;
  };
  std::vector<double> ticks;
  for (double v : preset) {
    if (v >= lo && v <= hi) ticks.push_back(v);
  }
  if (ticks.size() < 2 || !fits(ticks)) {
    for (const auto& m : std::vector<std::vector<double>>{{1, 2, 5}, {1, 3}, {1}}) {
      ticks = ticks_of(m, 1);
      if (fits(ticks) && ticks.size() >= 2) break;
    }
    for (int step = 2; !fits(ticks) && step < 10; ++step) ticks = ticks_of({1}, step);
  }
  vtkNew<vtkDoubleArray> at;
  vtkNew<vtkStringArray> names;
  for (double v : ticks) {
    at->InsertNextValue(std::log10(v));  // a log axis places its ticks in decades
    names->InsertNextValue(tick_text(v));
  }
  axis->SetCustomTickPositions(at, names);
}

// Draws a panel into its chart of `size` pixels (the plot area). `legend_room`: the fraction of
// the plot's height an inline legend at the top takes (the y axis grows by that much); 0: no
// inline legend.
void fill_chart(vtkChartXY* chart, const ChartPanel& p, double legend_room,
                const vtkVector2f& size) {
  chart->SetTitle(p.title);
  chart->GetTitleProperties()->SetFontSize(18);
  chart->GetTitleProperties()->BoldOn();
  style_axis(chart->GetAxis(vtkAxis::BOTTOM), p.x_label);
  style_axis(chart->GetAxis(vtkAxis::LEFT), p.y_label);
  // The series on top (the project's planner) are drawn last.
  std::vector<std::size_t> order;
  for (int top = 0; top < 2; ++top) {
    for (std::size_t k = 0; k < p.series.size(); ++k) {
      if (p.series[k].on_top == (top == 1)) order.push_back(k);
    }
  }
  int shown = 0;
  const std::size_t count = p.series.size();
  for (std::size_t k : order) {
    const ChartSeries& s = p.series[k];
    auto table = make_table(s, p.log_x, p.log_y);
    if (table->GetNumberOfRows() == 0) continue;
    // A single point is a marker (VTK's line plot refuses to draw it).
    vtkPlot* plot =
        chart->AddPlot(table->GetNumberOfRows() > 1 ? vtkChart::LINE : vtkChart::POINTS);
    plot->SetInputData(table, 0, 1);
    plot->SetLabel(s.name);
    plot->SetColor(s.rgb[0], s.rgb[1], s.rgb[2], s.alpha);
    // Earlier lines are drawn wider so that equal results stay visible under each other.
    const float shrink =
        count > 1 ? static_cast<float>(count - 1 - k) / static_cast<float>(count - 1) : 0.0f;
    const bool plain = s.alpha < 255 || s.on_top || !p.stagger_widths;
    plot->SetWidth(plain ? s.width : s.width + 2.0f * shrink);
    plot->GetPen()->SetLineType(s.line_type);
    if (auto* pts = vtkPlotPoints::SafeDownCast(plot)) {
      pts->SetMarkerStyle(s.marker);
      pts->SetMarkerSize(plain ? s.marker_size : s.marker_size + 5.0f * shrink);
    }
    ++shown;
  }
  chart->SetShowLegend(shown > 0 && legend_room > 0.0);
  chart->GetLegend()->SetHorizontalAlignment(vtkChartLegend::RIGHT);
  chart->GetLegend()->SetVerticalAlignment(vtkChartLegend::TOP);
  chart->GetLegend()->GetLabelProperties()->SetFontSize(kLegendFont);
  chart->GetLegend()->GetBrush()->SetColor(255, 255, 255, 215);

  const AxisRanges r = panel_ranges(p, legend_room);
  vtkAxis* bx = chart->GetAxis(vtkAxis::BOTTOM);
  vtkAxis* ly = chart->GetAxis(vtkAxis::LEFT);
  if (!p.x_tick_labels.empty()) {
    vtkNew<vtkDoubleArray> at;
    vtkNew<vtkStringArray> names;
    for (std::size_t k = 0; k < p.x_tick_labels.size(); ++k) {
      at->InsertNextValue(static_cast<double>(k));
      names->InsertNextValue(p.x_tick_labels[k]);
    }
    bx->SetCustomTickPositions(at, names);
    bx->GetLabelProperties()->SetOrientation(90.0);
    bx->GetLabelProperties()->SetJustificationToRight();
    bx->GetLabelProperties()->SetVerticalJustificationToCentered();
    bx->GetLabelProperties()->SetFontSize(13);
    bx->SetRange(r.x[0], r.x[1]);
  } else {
    bx->SetLogScale(p.log_x);
    bx->SetUnscaledRange(r.x[0], r.x[1]);
    if (p.log_x) set_log_ticks(bx, r.x[0], r.x[1], size[0], true, p.log_x_ticks);
  }
  bx->SetBehavior(vtkAxis::FIXED);
  ly->SetLogScale(p.log_y);
  ly->SetUnscaledRange(r.y[0], r.y[1]);
  if (p.log_y) set_log_ticks(ly, r.y[0], r.y[1], size[1], false, {});
  ly->SetBehavior(vtkAxis::FIXED);
}

}  // namespace

void write_chart_png(const std::string& title, const std::vector<ChartPanel>& panels, int columns,
                     const std::string& path, Overwrite overwrite, int width, int height,
                     bool shared_legend) {
  vtkNew<vtkContextView> view;
  vtkRenderWindow* win = view->GetRenderWindow();
  win->SetOffScreenRendering(1);
  win->SetSize(width, height);
  win->SetMultiSamples(0);
  view->GetRenderer()->SetBackground(1.0, 1.0, 1.0);

  const int n = static_cast<int>(panels.size());
  const int cols = std::max(1, std::min(columns, n));
  const int rows = (n + cols - 1) / cols;

  // One legend for the figure: the panel listing the most series lends its legend (every panel
  // draws a planner alike), placed in an empty cell, or else right of the panels.
  int legend_panel = -1;
  std::vector<std::string> legend_entries;
  if (shared_legend) {
    for (int i = 0; i < n; ++i) {
      auto names = legend_names(panels[static_cast<std::size_t>(i)]);
      if (names.size() > legend_entries.size()) {
        legend_entries = std::move(names);
        legend_panel = i;
      }
    }
  }

  // The charts' axes fill their rectangles: borders and gutters hold labels and titles.
  // Category axes write their names downwards: more room under each chart.
  std::size_t name_chars = 0;  // the longest category name
  for (const auto& p : panels) {
    for (const auto& t : p.x_tick_labels) name_chars = std::max(name_chars, t.size());
  }
  const bool names = name_chars > 0;
  const int name_room = static_cast<int>(7 * name_chars);  // 13-point names, written downwards
  const int bottom = names ? std::max(120, name_room + 25) : 72, top_border = 92;
  const vtkVector2f gutter(100.0f,
                           names ? static_cast<float>(std::max(170, name_room + 65)) : 110.0f);
  const float cell_h =
      (static_cast<float>(height - bottom - top_border) - gutter[1] * (rows - 1)) / rows;
  // The legend goes into the empty cell (the last row's) when it fits there, down into the
  // border below; else right of the panels over the whole height, in a smaller font if need be.
  int legend_font = kLegendFont;
  vtkVector2f legend = legend_size(legend_entries, legend_font);
  const bool legend_in_cell = legend_panel >= 0 && n < rows * cols &&
                              legend[1] <= cell_h + static_cast<float>(bottom) - 12.0f;
  if (legend_panel >= 0 && !legend_in_cell) {
    const auto room = static_cast<float>(height - top_border - 12);
    while (legend[1] > room && legend_font > kLegendFontMin) {
      legend = legend_size(legend_entries, --legend_font);
    }
  }
  const int border[4] = {
      95, bottom, legend_panel >= 0 && !legend_in_cell ? 60 + static_cast<int>(legend[0]) : 30,
      top_border};

  vtkNew<vtkChartMatrix> matrix;
  matrix->SetSize(vtkVector2i(cols, rows));
  matrix->SetBorders(border[0], border[1], border[2], border[3]);
  matrix->SetGutter(gutter);
  view->GetScene()->AddItem(matrix);
  const float cell_w =
      (static_cast<float>(width - border[0] - border[2]) - gutter[0] * (cols - 1)) / cols;
  vtkChartXY* legend_chart = nullptr;
  for (int i = 0; i < n; ++i) {
    const vtkVector2i pos(i % cols, rows - 1 - i / cols);
    auto* chart = vtkChartXY::SafeDownCast(matrix->GetChart(pos));
    if (chart == nullptr) continue;
    const ChartPanel& p = panels[static_cast<std::size_t>(i)];
    const auto entries = legend_names(p);
    const double room = !shared_legend && p.legend && !entries.empty()
                            ? (legend_size(entries)[1] + 8.0) / std::max(1.0f, cell_h)
                            : 0.0;
    fill_chart(chart, p, room, {cell_w, cell_h});
    if (i == legend_panel) legend_chart = chart;
  }
  if (legend_chart != nullptr) {
    // Top-left in the first empty cell, or right of the panels at the top.
    float x = static_cast<float>(width - border[2]) + 20.0f;
    float top = static_cast<float>(height - border[3]);
    if (legend_in_cell) {
      x = static_cast<float>(border[0]) + static_cast<float>(n % cols) * (cell_w + gutter[0]);
      top -= static_cast<float>(n / cols) * (cell_h + gutter[1]);
    }
    vtkChartLegend* l = legend_chart->GetLegend();
    legend_chart->SetShowLegend(true);
    l->GetLabelProperties()->SetFontSize(legend_font);
    l->SetHorizontalAlignment(vtkChartLegend::CUSTOM);
    l->SetVerticalAlignment(vtkChartLegend::CUSTOM);
    l->SetPoint(vtkVector2f(x, top - legend[1]));
  }

  vtkNew<vtkTextActor> heading;
  heading->SetInput(title.c_str());
  heading->GetTextProperty()->SetFontSize(22);
  heading->GetTextProperty()->BoldOn();
  heading->GetTextProperty()->SetColor(0.1, 0.1, 0.1);
  heading->GetTextProperty()->SetJustificationToCentered();
  heading->GetTextProperty()->SetVerticalJustificationToTop();
  heading->SetPosition(width / 2.0, height - 12.0);
  view->GetRenderer()->AddActor2D(heading);

  render_window_to_png(win, path, overwrite);
}

namespace {

struct SweepData {
  std::string dir;
  std::string summary_path;
  std::vector<RunPoint> runs;
  std::vector<ScenarioInfo> scenarios;
  std::map<std::string, PlannerStyle> styles;  // per label, over the whole sweep
};

SweepData load_sweep_data(const std::string& dir) {
  SweepData d;
  d.dir = dir;
  if (!fs::is_directory(dir))
    throw InputError(dir, "", "not a directory (expected a sweep output)");
  d.summary_path = (fs::path(dir) / "summary.csv").string();
  if (!fs::is_regular_file(d.summary_path)) {
    throw InputError(d.summary_path, "", "missing: not a sweep output directory");
  }
  const CsvTable s = read_csv(d.summary_path);
  const int c_run = s.require_column("run");
  const int c_scn = s.require_column("scenario");
  const int c_label = s.require_column("label");
  const int c_fpf = s.require_column("faces_per_frame");
  const int c_speed = s.require_column("speed_scale");
  const int c_fps = s.require_column("fps");
  const int c_frames = s.require_column("frames");
  const int c_dur = s.require_column("duration_s");
  const int c_p95 = s.require_column("error.viewed.de2000.p95");
  const int c_pops = s.require_column("pops.viewed.per_min");
  const int c_cov = s.require_column("coverage.mean");
  if (s.rows.empty()) throw InputError(d.summary_path, "", "no runs");

  std::map<std::string, double> us;
  const std::string timing_path = (fs::path(dir) / "timing.csv").string();
  if (fs::is_regular_file(timing_path)) {
    const CsvTable t = read_csv(timing_path);
    const int tr = t.require_column("run");
    const int tu = t.require_column("timing.planner_us_per_frame");
    for (std::size_t i = 0; i < t.rows.size(); ++i) us[t.text(i, tr)] = t.number(i, tu);
  }

  const int c_up95 = s.column("error.uniform.de2000.p95");
  const int c_upops = s.column("pops.uniform.per_min");
  const int c_bytes = s.column("memory.max_bytes");
  // Rows that differ only in their seed are one point: the mean over the seeds.
  std::map<std::tuple<std::string, std::string, double, double, double>, std::size_t> point_of;
  std::vector<std::vector<double>> sums;  // per point: p95, pops, coverage, us, bytes
  std::vector<std::vector<int>> counts;
  for (std::size_t i = 0; i < s.rows.size(); ++i) {
    const auto key = std::make_tuple(s.text(i, c_scn), s.text(i, c_label), s.number(i, c_fpf),
                                     s.number(i, c_speed), s.number(i, c_fps));
    auto [it, fresh] = point_of.try_emplace(key, d.runs.size());
    if (fresh) {
      RunPoint r;
      r.run = s.text(i, c_run);
      r.scenario = s.text(i, c_scn);
      r.label = s.text(i, c_label);
      r.faces_per_frame = s.number(i, c_fpf);
      r.speed_scale = s.number(i, c_speed);
      const double fps_col = s.number(i, c_fps);
      const double frames = s.number(i, c_frames), dur = s.number(i, c_dur);
      // fps 0: the scenario's own schedule; its mean rate is frames / duration.
      r.fps = fps_col > 0 ? fps_col : (dur > 0 ? frames / dur : kNaN);
      r.faces_per_s = r.faces_per_frame * r.fps;
      d.runs.push_back(std::move(r));
      sums.emplace_back(5, 0.0);
      counts.emplace_back(5, 0);
    }
    const std::size_t k = it->second;
    const double us_v = us.contains(s.text(i, c_run)) ? us[s.text(i, c_run)] : kNaN;
    const double v[5] = {s.number(i, c_p95), s.number(i, c_pops), s.number(i, c_cov), us_v,
                         c_bytes >= 0 ? s.number(i, c_bytes) : kNaN};
    for (int m = 0; m < 5; ++m) {
      if (std::isfinite(v[m])) {
        sums[k][m] += v[m];
        ++counts[k][m];
      }
    }
    d.runs[k].seed_runs.push_back(s.text(i, c_run));
    d.runs[k].per_seed.push_back({v[0], v[1], c_up95 >= 0 ? s.number(i, c_up95) : kNaN,
                                  c_upops >= 0 ? s.number(i, c_upops) : kNaN});
  }
  for (std::size_t k = 0; k < d.runs.size(); ++k) {
    const auto mean = [&](int m) { return counts[k][m] > 0 ? sums[k][m] / counts[k][m] : kNaN; };
    d.runs[k].de_p95 = mean(0);
    d.runs[k].pops_per_min = mean(1);
    d.runs[k].coverage = mean(2);
    d.runs[k].us_per_frame = mean(3);
    d.runs[k].max_bytes = mean(4);
  }
  std::vector<std::string> labels;
  for (const auto& r : d.runs) labels.push_back(r.label);
  d.styles = planner_styles(labels);
  for (const auto& r : d.runs) {
    auto it = std::find_if(d.scenarios.begin(), d.scenarios.end(),
                           [&](const ScenarioInfo& x) { return x.name == r.scenario; });
    if (it == d.scenarios.end()) {
      d.scenarios.push_back({r.scenario, false, {}});
      it = d.scenarios.end() - 1;
    }
    it->runs.push_back(&r);
  }
  // Camera speeds: the scenario's nominal speed from one run's result.json.
  for (auto& sc : d.scenarios) {
    double base = kNaN;
    for (const RunPoint* r : sc.runs) {
      const fs::path rj = fs::path(dir) / "runs" / r->run / "result.json";
      if (!fs::is_regular_file(rj)) continue;
      const auto speed = document_speed(load_json_file(rj.string()));
      if (speed && r->speed_scale > 0) base = *speed / r->speed_scale;
      break;
    }
    sc.speed_known = std::isfinite(base);
    for (const RunPoint* r : sc.runs) {
      const_cast<RunPoint*>(r)->speed = sc.speed_known ? base * r->speed_scale : r->speed_scale;
    }
  }
  return d;
}

// A series in the planner's style (colour, marker, line, width; on top for ambisim).
ChartSeries make_series(const SweepData& d, const std::string& name, const std::string& label) {
  const PlannerStyle& st = d.styles.at(label);
  ChartSeries s;
  s.name = name;
  std::copy(st.rgb.begin(), st.rgb.end(), s.rgb);
  s.marker = st.marker;
  s.line_type = st.line_type;
  s.width = st.width;
  s.marker_size = st.marker_size;
  s.on_top = st.emphasis;
  s.reference = st.reference;
  return s;
}

// Distinct values (sorted) of a field over runs.
template <class F>
std::vector<double> distinct(const std::vector<const RunPoint*>& runs, F f) {
  std::set<double> v;
  for (const RunPoint* r : runs) {
    const double x = f(*r);
    if (std::isfinite(x)) v.insert(x);
  }
  return {v.begin(), v.end()};
}

std::string join(const std::vector<double>& v, const char* unit) {
  std::string s;
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + fmt(v[i]);
  return s + unit;
}

// Points of one series sorted by x.
void sort_by_x(ChartSeries& s) {
  std::vector<std::size_t> idx(s.x.size());
  for (std::size_t i = 0; i < idx.size(); ++i) idx[i] = i;
  std::stable_sort(idx.begin(), idx.end(),
                   [&](std::size_t a, std::size_t b) { return s.x[a] < s.x[b]; });
  std::vector<double> x, y;
  for (std::size_t i : idx) {
    x.push_back(s.x[i]);
    y.push_back(s.y[i]);
  }
  s.x = std::move(x);
  s.y = std::move(y);
}

// The Pareto front (lower x and lower y both better) of all finite points of the series, the
// references (the oracle: no budget, no game can run it) left out.
ChartSeries pareto_front(const std::vector<ChartSeries>& series, bool log_x) {
  std::vector<std::pair<double, double>> pts;
  bool without = false;
  for (const auto& s : series) {
    without = without || s.reference;
    if (s.reference) continue;
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      if (log_x && !(s.x[i] > 0.0)) continue;
      if (std::isfinite(s.x[i]) && std::isfinite(s.y[i])) pts.emplace_back(s.x[i], s.y[i]);
    }
  }
  std::sort(pts.begin(), pts.end());
  // A staircase: the best error so far holds as the cost grows until the next point of the
  // front (never interpolated between planners).
  ChartSeries f;
  f.name = without ? "Pareto front (no oracle)" : "Pareto front";
  f.rgb[0] = f.rgb[1] = f.rgb[2] = 60;
  f.alpha = 70;
  f.width = 12.0f;
  f.marker = 0;
  double best = std::numeric_limits<double>::infinity();
  for (const auto& [x, y] : pts) {
    if (y < best) {
      if (!f.x.empty()) {
        f.x.push_back(x);
        f.y.push_back(best);
      }
      f.x.push_back(x);
      f.y.push_back(y);
      best = y;
    }
  }
  return f;
}

// Runs at the scenario's nominal speed (the speed scale closest to 1).
std::vector<const RunPoint*> at_nominal_speed(const ScenarioInfo& sc, double* scale) {
  const auto scales = distinct(sc.runs, [](const RunPoint& r) { return r.speed_scale; });
  double best = scales.empty() ? 1.0 : scales[0];
  for (double s : scales) {
    if (std::fabs(std::log(s > 0 ? s : 1e-9)) < std::fabs(std::log(best > 0 ? best : 1e-9)))
      best = s;
  }
  *scale = best;
  std::vector<const RunPoint*> out;
  for (const RunPoint* r : sc.runs) {
    if (r->speed_scale == best || (!std::isfinite(best) && !std::isfinite(r->speed_scale)))
      out.push_back(r);
  }
  return out;
}

std::string speed_text(const ScenarioInfo& sc, const std::vector<const RunPoint*>& runs) {
  const auto v = distinct(runs, [](const RunPoint& r) { return r.speed; });
  return sc.speed_known ? "camera " + join(v, " m/s") : "speed scale " + join(v, "x");
}

// The k-th variant of a planner's series (another fps or budget): its colour, another line
// type and marker.
void vary_style(ChartSeries& s, int k) {
  if (k == 0) return;
  s.line_type = 1 + (s.line_type - 1 + k) % 4;
  s.marker = marker_variant(s.marker, k);
}

// Lines per planner label (and per fps when several), x and y picked by the functions.
template <class FX, class FY>
std::vector<ChartSeries> lines_by_label(const SweepData& d,
                                        const std::vector<const RunPoint*>& runs, FX fx, FY fy) {
  const bool many_fps = distinct(runs, [](const RunPoint& r) { return r.fps; }).size() > 1;
  const auto fps_values = distinct(runs, [](const RunPoint& r) { return r.fps; });
  std::vector<ChartSeries> out;
  std::vector<std::string> keys;
  for (const RunPoint* r : runs) {
    std::string key = r->label;
    int style = 0;
    if (many_fps) {
      key += " @ " + fmt(r->fps) + " fps";
      style = static_cast<int>(std::find(fps_values.begin(), fps_values.end(), r->fps) -
                               fps_values.begin());
    }
    auto it = std::find(keys.begin(), keys.end(), key);
    if (it == keys.end()) {
      keys.push_back(key);
      out.push_back(make_series(d, key, r->label));
      vary_style(out.back(), style);
      it = keys.end() - 1;
    }
    ChartSeries& s = out[static_cast<std::size_t>(it - keys.begin())];
    s.x.push_back(fx(*r));
    s.y.push_back(fy(*r));
  }
  for (auto& s : out) sort_by_x(s);
  return out;
}

bool wide_range(const std::vector<double>& v) {
  return v.size() >= 3 && v.front() > 0 && v.back() / v.front() >= 8.0;
}

std::string fps_text(const std::vector<const RunPoint*>& runs) {
  return join(distinct(runs, [](const RunPoint& r) { return r.fps; }), " fps");
}

std::vector<ChartPanel> accuracy_cost_panels(const SweepData& d, const ScenarioInfo& sc,
                                             std::string* title) {
  double scale = 1.0;
  const auto runs = at_nominal_speed(sc, &scale);
  *title =
      sc.name + ": accuracy against cost (" + speed_text(sc, runs) + ", " + fps_text(runs) + ")";
  ChartPanel a;
  a.title = "viewed ΔE00 p95 vs capture budget";
  a.x_label = "capture budget (cube faces per second)";
  a.y_label = "viewed ΔE00 p95 (CIEDE2000)";
  a.series = lines_by_label(
      d, runs, [](const RunPoint& r) { return r.faces_per_s; },
      [](const RunPoint& r) { return r.de_p95; });
  a.log_x = wide_range(distinct(runs, [](const RunPoint& r) { return r.faces_per_s; }));
  a.log_x_ticks = distinct(runs, [](const RunPoint& r) { return r.faces_per_s; });
  a.stagger_widths = true;
  a.series.insert(a.series.begin(), pareto_front(a.series, a.log_x));

  // Costs a planner does not order (a point per budget): markers only, log axes when they span
  // a decade or so.
  const auto scatter = [&](const char* name, const char* x_label, auto fx) {
    ChartPanel p;
    p.title = name;
    p.x_label = x_label;
    p.y_label = "viewed ΔE00 p95 (CIEDE2000)";
    p.series = lines_by_label(d, runs, fx, [](const RunPoint& r) { return r.de_p95; });
    for (auto& s : p.series) s.line_type = 0;
    p.log_x = wide_range(distinct(runs, fx));
    p.stagger_widths = true;
    p.series.insert(p.series.begin(), pareto_front(p.series, p.log_x));
    return p;
  };
  std::vector<ChartPanel> out = {
      a, scatter("viewed ΔE00 p95 vs planner CPU time", "planner time per frame (µs, measured)",
                 [](const RunPoint& r) { return r.us_per_frame; })};
  if (!distinct(runs, [](const RunPoint& r) { return r.max_bytes; }).empty()) {
    out.push_back(scatter("viewed ΔE00 p95 vs planner memory", "planner memory, peak (KiB)",
                          [](const RunPoint& r) { return r.max_bytes / 1024.0; }));
  }
  return out;
}

std::vector<ChartPanel> speed_panels(const SweepData& d, const ScenarioInfo& sc,
                                     std::string* title) {
  const auto budgets = distinct(sc.runs, [](const RunPoint& r) { return r.faces_per_s; });
  // One line per planner at the median budget: with a dozen planners, a line per planner and
  // budget makes an unreadable legend (the accuracy-cost chart shows the budget axis).
  std::vector<double> shown = {budgets[budgets.size() / 2]};
  std::vector<const RunPoint*> runs;
  for (const RunPoint* r : sc.runs) {
    if (std::find(shown.begin(), shown.end(), r->faces_per_s) != shown.end()) runs.push_back(r);
  }
  *title = sc.name + ": error and pops against camera speed (budget " + join(shown, " faces/s") +
           ", " + fps_text(runs) + ")";
  // A line per planner (and per frame rate when the sweep has several).
  const auto fps_values = distinct(runs, [](const RunPoint& r) { return r.fps; });
  auto make = [&](auto fy) {
    std::vector<ChartSeries> out;
    std::vector<std::string> keys;
    for (const RunPoint* r : runs) {
      const auto fi = std::find(fps_values.begin(), fps_values.end(), r->fps) - fps_values.begin();
      const auto bi = std::find(shown.begin(), shown.end(), r->faces_per_s) - shown.begin();
      std::string key = r->label;
      if (shown.size() > 1) key += ", " + fmt(r->faces_per_s) + " faces/s";
      if (fps_values.size() > 1) key += " @ " + fmt(r->fps) + " fps";
      auto it = std::find(keys.begin(), keys.end(), key);
      if (it == keys.end()) {
        keys.push_back(key);
        out.push_back(make_series(d, key, r->label));
        vary_style(out.back(), static_cast<int>(bi * std::ssize(fps_values) + fi));
        it = keys.end() - 1;
      }
      ChartSeries& s = out[static_cast<std::size_t>(it - keys.begin())];
      s.x.push_back(r->speed);
      s.y.push_back(fy(*r));
    }
    for (auto& s : out) sort_by_x(s);
    return out;
  };
  const std::string x_label =
      sc.speed_known ? "camera speed (m/s)" : "camera speed (x the scenario's speed)";
  ChartPanel a;
  a.title = "viewed ΔE00 p95 vs camera speed";
  a.x_label = x_label;
  a.y_label = "viewed ΔE00 p95 (CIEDE2000)";
  a.series = make([](const RunPoint& r) { return r.de_p95; });
  ChartPanel b;
  b.title = "viewed colour pops vs camera speed";
  b.x_label = x_label;
  b.y_label = "viewed pops per viewed receiver-minute";
  b.series = make([](const RunPoint& r) { return r.pops_per_min; });
  a.stagger_widths = b.stagger_widths = true;
  return {a, b};
}

std::vector<ChartPanel> coverage_panels(const SweepData& d, const ScenarioInfo& sc,
                                        std::string* title) {
  double scale = 1.0;
  const auto runs = at_nominal_speed(sc, &scale);
  *title = sc.name + ": coverage against capture budget (" + speed_text(sc, runs) + ", " +
           fps_text(runs) + ")";
  ChartPanel a;
  a.title = "probe coverage vs capture budget";
  a.x_label = "capture budget (cube faces per second)";
  a.y_label = "coverage (fraction of demand points served)";
  a.series = lines_by_label(
      d, runs, [](const RunPoint& r) { return r.faces_per_s; },
      [](const RunPoint& r) { return r.coverage; });
  a.stagger_widths = true;
  a.log_x = wide_range(distinct(runs, [](const RunPoint& r) { return r.faces_per_s; }));
  a.log_x_ticks = distinct(runs, [](const RunPoint& r) { return r.faces_per_s; });
  return {a};
}

// Box plots across seeds at the nominal speed and the budget nearest 1 face per frame: per
// planner the range (whisker), the quartiles (box) and median (nearest rank) and every seed.
std::vector<ChartPanel> seed_panels(const SweepData& d, const ScenarioInfo& sc,
                                    std::string* title) {
  double scale = 1.0;
  auto runs = at_nominal_speed(sc, &scale);
  const auto budgets = distinct(runs, [](const RunPoint& r) { return r.faces_per_frame; });
  double budget = budgets.empty() ? 1.0 : budgets[0];
  for (double b : budgets) {
    if (std::fabs(std::log(b > 0 ? b : 1e-9)) < std::fabs(std::log(budget > 0 ? budget : 1e-9)))
      budget = b;
  }
  std::erase_if(runs, [&](const RunPoint* r) { return r->faces_per_frame != budget; });
  std::size_t seeds = 0;
  for (const RunPoint* r : runs) seeds = std::max(seeds, r->per_seed.size());
  *title = sc.name + ": across " + std::to_string(seeds) + " seeds (" + speed_text(sc, runs) +
           ", " + fmt(budget) + (budget == 1.0 ? " face/frame)" : " faces/frame)");
  struct Metric {
    const char* title;
    const char* y_label;
    double RunPoint::Seed::*field;
  };
  const Metric metrics[] = {
      {"viewed ΔE00 p95", "viewed ΔE00 p95", &RunPoint::Seed::viewed_p95},
      {"viewed colour pops", "pops per viewed receiver-minute", &RunPoint::Seed::viewed_pops},
      {"uniform ΔE00 p95", "ΔE00 p95, every receiver and normal", &RunPoint::Seed::uniform_p95},
      {"uniform colour pops", "pops per receiver-minute", &RunPoint::Seed::uniform_pops}};
  std::vector<ChartPanel> out;
  for (const Metric& m : metrics) {
    ChartPanel p;
    p.title = m.title;
    p.y_label = m.y_label;  // the x axis names the planners
    p.legend = false;
    for (std::size_t k = 0; k < runs.size(); ++k) {
      const RunPoint& r = *runs[k];
      p.x_tick_labels.push_back(r.label);
      std::vector<double> v;
      for (const auto& sd : r.per_seed) {
        if (std::isfinite(sd.*m.field)) v.push_back(sd.*m.field);
      }
      if (v.empty()) continue;
      const double x = static_cast<double>(k);
      const auto q = [&](double pc) { return percentile_nearest_rank(v, pc); };
      // In the planner's colour (ambisim's boxes bolder); every seed in its marker.
      const ChartSeries style = make_series(d, "", r.label);
      const float bold = style.on_top ? 1.6f : 1.0f;
      const auto part = [&](std::vector<double> xs, std::vector<double> ys, float width) {
        ChartSeries s = style;
        s.x = std::move(xs);
        s.y = std::move(ys);
        s.line_type = 1;
        s.marker = 0;
        s.width = width * bold;
        p.series.push_back(std::move(s));
      };
      part({x, x}, {q(0), q(100)}, 1.5f);
      part({x - 0.3, x + 0.3, x + 0.3, x - 0.3, x - 0.3}, {q(25), q(25), q(75), q(75), q(25)},
           2.0f);
      part({x - 0.3, x + 0.3}, {q(50), q(50)}, 4.0f);
      ChartSeries dots = style;
      dots.line_type = 0;
      dots.marker_size = style.on_top ? 9.0f : 7.0f;
      for (double y : v) {
        dots.x.push_back(x);
        dots.y.push_back(y);
      }
      p.series.push_back(std::move(dots));
    }
    out.push_back(std::move(p));
  }
  return out;
}

std::vector<double> json_series(const nlohmann::json& series, const char* key) {
  std::vector<double> out;
  if (!series.contains(key) || !series[key].is_array()) return out;
  for (const auto& v : series[key]) out.push_back(v.is_number() ? v.get<double>() : kNaN);
  return out;
}

std::vector<ChartPanel> series_panels(const RunPoint& run, bool speed_known,
                                      const std::string& result_path, std::string* title) {
  const nlohmann::json result = load_json_file(result_path);
  if (!result.contains("series") || !result["series"].is_object()) {
    throw InputError(result_path, "/series", "missing (not a run result)");
  }
  const auto& s = result["series"];
  const auto t = json_series(s, "time");
  if (t.empty()) throw InputError(result_path, "/series/time", "missing or empty");
  std::string planner = run.label;
  *title = run.scenario + " / " + planner + ": time series of run " + run.run + " (" +
           fmt(run.faces_per_s) + " faces/s, " + fmt(run.fps) + " fps, " + fmt(run.speed) +
           (speed_known ? " m/s)" : "x speed)");
  auto line = [&](const std::string& name, const std::vector<double>& y, int colour) {
    ChartSeries c;
    c.name = name;
    c.x = t;
    c.y = y;
    std::copy(kSeriesColours[colour], kSeriesColours[colour] + 3, c.rgb);
    c.marker = 0;
    c.width = 2.0f;
    return c;
  };
  ChartPanel err;
  err.title = "error at the receivers";
  err.x_label = "time (s)";
  err.y_label = "ΔE00 (CIEDE2000)";
  err.series = {line("max over receivers", json_series(s, "de2000_max"), 1),
                line("mean over receivers", json_series(s, "de2000_mean"), 0),
                line("viewed mean", json_series(s, "de2000_viewed_mean"), 4)};
  ChartPanel pops;
  pops.title = "colour pops";
  pops.x_label = "time (s)";
  pops.y_label = "pops so far (count)";
  {
    const auto cumulative = [&](const char* key) {
      auto p = json_series(s, key);
      double sum = 0.0;
      for (double& v : p) {
        if (std::isfinite(v)) sum += v;
        v = sum;
      }
      return p;
    };
    pops.series = {line("cumulative pops (all receivers)", cumulative("pops"), 3),
                   line("cumulative pops where seen", cumulative("viewed_pops"), 5)};
  }
  ChartPanel live;
  live.title = "planner state";
  live.x_label = "time (s)";
  live.y_label = "count";
  live.series = {line("live probes", json_series(s, "live_probes"), 2),
                 line("receivers", json_series(s, "receivers"), 7)};
  ChartPanel cov;
  cov.title = "coverage";
  cov.x_label = "time (s)";
  cov.y_label = "fraction of demand points served";
  cov.series = {line("coverage", json_series(s, "coverage"), 4)};
  return {err, pops, live, cov};
}

// Whether a run's scenario document lights its world differently over time: a sun on a path,
// or clouds, street lamps or fog that are not switched off.
bool light_changes(const nlohmann::json& result) {
  const nlohmann::json* w = &result;
  for (const char* key : {"scenario", "document", "world"}) {
    if (!w->is_object() || !w->contains(key)) return false;
    w = &(*w)[key];
  }
  if (w->contains("sun") && (*w)["sun"].is_object() && (*w)["sun"].contains("path")) return true;
  for (const char* key : {"clouds", "lamps", "fog"}) {
    if (!w->contains(key) || !(*w)[key].is_object()) continue;
    const auto& o = (*w)[key];
    if (!o.contains("enabled") || o["enabled"] != false) return true;
  }
  return false;
}

TimeAxis time_axis(const nlohmann::json& result) {
  TimeAxis a;
  const nlohmann::json* p = &result;
  for (const char* key : {"scenario", "document", "world", "sun", "path"}) {
    if (!p->is_object() || !p->contains(key)) return a;
    p = &(*p)[key];
  }
  if (p->value("type", "") != "solar") return a;
  const std::string start = p->value("start", "00:00");
  int h = 0, m = 0;
  if (std::sscanf(start.c_str(), "%d:%d", &h, &m) < 1) return a;
  a.start = h + m / 60.0;
  a.scale = p->value("time_scale", 1.0) / 3600.0;
  a.label = "local time of day (h)";
  return a;
}

// Viewed and uniform mean error over the time of day (or the run's time) for every planner at
// the sweep's nominal speed and the budget nearest 1 face per frame: each seed's series
// (result.json) averaged over the seeds, in kTimeBins bins.
std::vector<ChartPanel> light_panels(const SweepData& d, const ScenarioInfo& sc,
                                     std::string* title) {
  constexpr int kTimeBins = 120;
  double scale = 1.0;
  const auto runs = at_nominal_speed(sc, &scale);
  double budget = kNaN;
  for (const RunPoint* r : runs) {
    if (!std::isfinite(budget) || std::fabs(r->faces_per_frame - 1.0) < std::fabs(budget - 1.0)) {
      budget = r->faces_per_frame;
    }
  }
  ChartPanel viewed, uniform;
  viewed.title = "error where the player looks (viewed mean)";
  uniform.title = "error at every receiver and normal (uniform mean)";
  viewed.y_label = uniform.y_label = "ΔE00 (CIEDE2000)";
  TimeAxis axis;
  for (const RunPoint* r : runs) {
    if (r->faces_per_frame != budget) continue;
    std::vector<double> xs, sum_v, sum_u;
    std::vector<int> n_v, n_u;
    for (const auto& id : r->seed_runs) {
      const fs::path rp = fs::path(d.dir) / "runs" / id / "result.json";
      if (!fs::is_regular_file(rp)) continue;
      const nlohmann::json result = load_json_file(rp.string());
      axis = time_axis(result);
      const auto& series = result.contains("series") ? result["series"] : nlohmann::json();
      const auto t = json_series(series, "time");
      const auto v = json_series(series, "de2000_viewed_mean");
      const auto u = json_series(series, "de2000_mean");
      if (t.empty() || v.size() != t.size() || u.size() != t.size()) continue;
      const double t_end = t.back() > 0.0 ? t.back() : 1.0;
      if (xs.empty()) {
        xs.resize(kTimeBins);
        for (int b = 0; b < kTimeBins; ++b) {
          xs[static_cast<std::size_t>(b)] = axis.start + axis.scale * t_end * (b + 0.5) / kTimeBins;
        }
        sum_v.assign(kTimeBins, 0.0);
        sum_u.assign(kTimeBins, 0.0);
        n_v.assign(kTimeBins, 0);
        n_u.assign(kTimeBins, 0);
      }
      for (std::size_t i = 0; i < t.size(); ++i) {
        const int b = std::clamp(static_cast<int>(t[i] / t_end * kTimeBins), 0, kTimeBins - 1);
        const auto bi = static_cast<std::size_t>(b);
        if (std::isfinite(v[i])) sum_v[bi] += v[i], ++n_v[bi];
        if (std::isfinite(u[i])) sum_u[bi] += u[i], ++n_u[bi];
      }
    }
    if (xs.empty()) continue;
    // A line per run of bins with data: where no receiver is in view (the viewed mean is
    // undefined) the line stops instead of bridging the gap. The first piece carries the name.
    const auto add_pieces = [&](ChartPanel& panel, const std::vector<double>& sum,
                                const std::vector<int>& n) {
      ChartSeries piece = make_series(d, r->label, r->label);
      piece.marker = 0;
      bool named = false;
      const auto flush = [&] {
        if (piece.x.empty()) return;
        if (named) piece.name.clear();
        named = true;
        panel.series.push_back(piece);
        piece.x.clear();
        piece.y.clear();
      };
      for (int k = 0; k < kTimeBins; ++k) {
        const auto bi = static_cast<std::size_t>(k);
        if (n[bi] == 0) {
          flush();
          continue;
        }
        piece.x.push_back(xs[bi]);
        piece.y.push_back(sum[bi] / n[bi]);
      }
      flush();
    };
    add_pieces(viewed, sum_v, n_v);
    add_pieces(uniform, sum_u, n_u);
  }
  viewed.x_label = uniform.x_label = axis.label;
  viewed.y_from_zero = uniform.y_from_zero = true;
  *title = sc.name + ": error as the light changes (budget " + fmt(budget) +
           " faces/frame, mean over seeds)";
  return {viewed, uniform};
}

std::string safe_name(const std::string& s) {
  std::string out;
  for (char c : s) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '_' || c == '-' || c == '.';
    out += ok ? c : '_';
  }
  return out.empty() ? "unnamed" : out;
}

}  // namespace

bool scenario_light_changes(const nlohmann::json& result) { return light_changes(result); }

TimeAxis light_time_axis(const nlohmann::json& result) { return time_axis(result); }

std::vector<std::string> write_sweep_charts(const std::string& sweep_dir,
                                            const PlotOptions& options) {
  const SweepData d = load_sweep_data(sweep_dir);
  const RunPoint* chosen = nullptr;
  if (!options.run_id.empty()) {
    for (const auto& r : d.runs) {
      if (r.run == options.run_id) chosen = &r;
    }
    if (chosen == nullptr) {
      throw InputError(d.summary_path, "", "unknown run id '" + options.run_id + "'");
    }
  }
  struct Job {
    std::string path, title;
    std::vector<ChartPanel> panels;
    int columns;
    const RunPoint* series_run = nullptr;
    bool speed_known = false;
    double height_scale = 1.0;   // taller for the planner names under box plots
    bool shared_legend = false;  // one legend for the figure (the panels draw the same planners)
  };
  const fs::path charts = fs::path(sweep_dir) / "charts";
  std::vector<Job> jobs;
  for (const auto& sc : d.scenarios) {
    const std::string base = safe_name(sc.name);
    Job a{(charts / (base + "_accuracy_cost.png")).string(), "", {}, 2};
    a.panels = accuracy_cost_panels(d, sc, &a.title);
    if (a.panels.size() > 2) a.height_scale = 1.5;  // two rows, the legend in the fourth cell
    Job b{(charts / (base + "_speed.png")).string(), "", {}, 2};
    b.panels = speed_panels(d, sc, &b.title);
    Job c{(charts / (base + "_coverage_budget.png")).string(), "", {}, 1};
    c.panels = coverage_panels(d, sc, &c.title);
    a.shared_legend = b.shared_legend = c.shared_legend = true;
    jobs.push_back(std::move(a));
    jobs.push_back(std::move(b));
    jobs.push_back(std::move(c));
    const bool several_seeds = std::any_of(
        sc.runs.begin(), sc.runs.end(), [](const RunPoint* r) { return r->per_seed.size() > 1; });
    if (several_seeds) {
      Job e{(charts / (base + "_seeds.png")).string(), "", {}, 2};
      e.panels = seed_panels(d, sc, &e.title);
      e.height_scale = 1.3;
      jobs.push_back(std::move(e));
    }
    {
      const fs::path rj = fs::path(sweep_dir) / "runs" / sc.runs.front()->run / "result.json";
      if (fs::is_regular_file(rj) && light_changes(load_json_file(rj.string()))) {
        Job l{(charts / (base + "_light.png")).string(), "", {}, 2};
        l.panels = light_panels(d, sc, &l.title);
        l.shared_legend = true;
        jobs.push_back(std::move(l));
      }
    }
    const RunPoint* sr =
        chosen ? (chosen->scenario == sc.name ? chosen : nullptr) : sc.runs.front();
    if (sr != nullptr) {
      Job s{(charts / (safe_name(sr->run) + "_series.png")).string(), "", {}, 2};
      s.series_run = sr;
      s.speed_known = sc.speed_known;
      jobs.push_back(std::move(s));
    }
  }
  // Time series inputs and every output path are checked before anything is written.
  for (auto& j : jobs) {
    if (j.series_run == nullptr) continue;
    const std::string rp =
        (fs::path(sweep_dir) / "runs" / j.series_run->run / "result.json").string();
    if (!fs::is_regular_file(rp)) throw InputError(rp, "", "missing: no result for this run");
    j.panels = series_panels(*j.series_run, j.speed_known, rp, &j.title);
  }
  std::error_code ec;
  fs::create_directories(charts, ec);
  if (ec) throw InputError(charts.string(), "", "cannot create directory: " + ec.message());
  for (const auto& j : jobs) check_output_path(j.path, options.overwrite);
  std::vector<std::string> written;
  for (const auto& j : jobs) {
    write_chart_png(j.title, j.panels, j.columns, j.path, options.overwrite, options.width,
                    static_cast<int>(options.height * j.height_scale), j.shared_legend);
    written.push_back(j.path);
  }
  return written;
}

}  // namespace ambisim
