#include "viz/bench_chart.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>

#include <nlohmann/json.hpp>

#include "sim/base/input_error.h"
#include "viz/charts.h"
#include "viz/planner_style.h"

namespace ambisim {
namespace {

double to_ns(double t, const std::string& unit) {
  if (unit == "us") return t * 1e3;
  if (unit == "ms") return t * 1e6;
  if (unit == "s") return t * 1e9;
  return t;  // "ns"
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::size_t start = 0;
  for (;;) {
    const std::size_t at = s.find(sep, start);
    out.push_back(s.substr(start, at - start));
    if (at == std::string::npos) return out;
    start = at + 1;
  }
}

double number_or(const nlohmann::json& j, const char* key, double fallback) {
  const auto it = j.find(key);
  return it != j.end() && it->is_number() ? it->get<double>() : fallback;
}

// Google Benchmark writes NaN (and inf) for the spread of a counter that does not vary, which is
// not JSON: such values become null before parsing.
nlohmann::json load_benchmark_json(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(path, ec)) throw InputError(path, "", "no such file");
  if (fs::is_directory(path, ec)) throw InputError(path, "", "is a directory, not a JSON file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "", "cannot be opened for reading");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  static const std::regex kNonFinite(R"((:\s*)-?(NaN|nan|inf|Infinity)\b)");
  const std::string text = std::regex_replace(buffer.str(), kNonFinite, "$1null");
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(path, "", std::string("invalid JSON: ") + e.what());
  }
}

}  // namespace

std::vector<PlannerBenchPoint> read_planner_bench(const std::string& path) {
  const nlohmann::json doc = load_benchmark_json(path);
  if (!doc.is_object() || !doc.contains("benchmarks") || !doc["benchmarks"].is_array()) {
    throw InputError(path, "/benchmarks",
                     "missing: not Google Benchmark JSON (--benchmark_out_format=json)");
  }
  const auto& entries = doc["benchmarks"];
  // With --benchmark_repetitions, use the medians; otherwise the plain iterations.
  const bool medians = std::any_of(entries.begin(), entries.end(), [](const nlohmann::json& e) {
    return e.is_object() && e.value("aggregate_name", "") == "median";
  });
  std::map<std::string, PlannerBenchPoint> by_run;  // one point per run name (last wins)
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const nlohmann::json& e = entries[i];
    const std::string where = "/benchmarks/" + std::to_string(i);
    if (!e.is_object()) throw InputError(path, where, "must be an object");
    const std::string type = e.value("run_type", "iteration");
    if (medians ? e.value("aggregate_name", "") != "median" : type != "iteration") continue;
    if (e.contains("error_occurred") && e["error_occurred"] == true) continue;
    const std::string run = e.value("run_name", e.value("name", ""));
    const std::vector<std::string> parts = split(run, '/');
    PlannerBenchPoint p;
    std::string n;
    if ((parts[0] == "BM_Lookup" || parts[0] == "BM_Frame") && parts.size() >= 3) {
      p.kind = parts[0] == "BM_Lookup" ? "lookup" : "frame";
      p.planner = parts[1];
      n = parts[2];
    } else if (parts[0] == "BM_LookupNaive" && parts.size() >= 2) {
      p.kind = "lookup_naive";
      n = parts[1];
    } else {
      continue;  // some other benchmark of the file
    }
    try {
      p.target = std::stod(n);
    } catch (const std::exception&) {
      throw InputError(path, where + "/run_name", "expected .../<live probes>, got " + run);
    }
    if (!e.contains("real_time") || !e["real_time"].is_number()) {
      throw InputError(path, where + "/real_time", "missing or not a number");
    }
    p.ns = to_ns(e["real_time"].get<double>(), e.value("time_unit", "ns"));
    p.live = number_or(e, "live", p.target);
    by_run[run] = p;
  }
  std::vector<PlannerBenchPoint> out;
  for (auto& [run, p] : by_run) out.push_back(p);
  if (std::none_of(out.begin(), out.end(),
                   [](const PlannerBenchPoint& p) { return p.kind != "lookup_naive"; })) {
    throw InputError(path, "/benchmarks",
                     "no BM_Lookup or BM_Frame entries (bench_planners output?)");
  }
  return out;
}

void write_planner_bench_chart(const std::string& bench_json, const std::string& png,
                               Overwrite overwrite, int width, int height) {
  check_output_path(png, overwrite);
  std::vector<PlannerBenchPoint> points = read_planner_bench(bench_json);
  std::sort(points.begin(), points.end(), [](const auto& a, const auto& b) {
    return std::tie(a.kind, a.planner, a.live) < std::tie(b.kind, b.planner, b.live);
  });
  // Every planner in its style, as in the sweep charts.
  std::vector<std::string> planners;
  for (const auto& p : points) {
    if (!p.planner.empty()) planners.push_back(p.planner);
  }
  const auto styles = planner_styles(planners);

  ChartPanel lookup, frame;
  lookup.title = "lookup";
  lookup.x_label = "live probes";
  lookup.y_label = "ns per lookup";
  frame.title = "planner work per frame (1 face/frame)";
  frame.x_label = "live probes";
  frame.y_label = "us per frame";
  for (ChartPanel* panel : {&lookup, &frame}) panel->log_x = panel->log_y = true;

  const auto series_for = [&](ChartPanel& panel, const std::string& name) -> ChartSeries& {
    for (auto& s : panel.series) {
      if (s.name == name) return s;
    }
    ChartSeries s;
    s.name = name;
    if (const auto it = styles.find(name); it != styles.end()) {
      const PlannerStyle& st = it->second;
      std::copy(st.rgb.begin(), st.rgb.end(), s.rgb);
      s.marker = st.marker;
      s.line_type = st.line_type;
      s.width = st.width;
      s.marker_size = st.marker_size;
      s.on_top = st.emphasis;
    }
    panel.series.push_back(s);
    return panel.series.back();
  };
  for (const auto& p : points) {
    if (p.kind == "lookup_naive") {
      ChartSeries& s = series_for(lookup, "naive linear scan");
      s.rgb[0] = s.rgb[1] = s.rgb[2] = 90;
      s.line_type = 3;
      s.marker = 0;
      s.x.push_back(p.live);
      s.y.push_back(p.ns);
    } else if (p.kind == "lookup") {
      ChartSeries& s = series_for(lookup, p.planner);
      s.x.push_back(p.live);
      s.y.push_back(p.ns);
    } else {
      ChartSeries& s = series_for(frame, p.planner);
      s.x.push_back(p.live);
      s.y.push_back(p.ns / 1e3);
    }
  }
  write_chart_png("Planner cost against live probes (bench_planners)", {lookup, frame}, 2, png,
                  overwrite, width, height, /*shared_legend=*/true);
}

}  // namespace ambisim
