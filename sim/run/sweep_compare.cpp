#include "sim/run/sweep_compare.h"

#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <tuple>

#include "sim/base/hash.h"
#include "sim/base/input_error.h"

namespace ambisim {
namespace {

struct Condition {
  std::string scenario;
  double faces_per_frame, speed_scale, fps;
  bool operator<(const Condition& o) const {
    return std::tie(scenario, faces_per_frame, speed_scale, fps) <
           std::tie(o.scenario, o.faces_per_frame, o.speed_scale, o.fps);
  }
};

std::uint64_t text_hash(std::uint64_t h, const std::string& s) {
  ContentHasher c;
  c.add_value(h);
  c.add_bytes(s.data(), s.size());
  return c.value();
}

std::string number(double x, int digits = 3) {
  if (!std::isfinite(x)) return "nan";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.*g", digits, x);
  return buf;
}

std::string fixed(double x) {
  if (!std::isfinite(x)) return "-";
  char buf[32];
  std::snprintf(buf, sizeof buf,
                std::abs(x) >= 100 ? "%.0f" : (std::abs(x) >= 10 ? "%.1f" : "%.2f"), x);
  return buf;
}

}  // namespace

const std::vector<std::string>& default_compare_metrics() {
  static const std::vector<std::string> m = {"error.viewed.de2000.p95",  "pops.viewed.per_min",
                                             "error.uniform.de2000.p95", "pops.uniform.per_min",
                                             "response.median_s",        "coverage.mean"};
  return m;
}

bool higher_is_better(const std::string& metric) { return metric.rfind("coverage.", 0) == 0; }

std::vector<CompareRow> compare_sweep(const CsvTable& t, const std::string& baseline,
                                      const std::vector<std::string>& metrics) {
  const int c_scn = t.require_column("scenario");
  const int c_label = t.require_column("label");
  const int c_fpf = t.require_column("faces_per_frame");
  const int c_speed = t.require_column("speed_scale");
  const int c_fps = t.require_column("fps");
  const int c_seed = t.require_column("seed");
  std::vector<int> c_metric;
  for (const auto& m : metrics) {
    const int c = t.column(m);
    if (c < 0) {
      std::string valid;
      for (const auto& h : t.header) {
        if (h.find('.') != std::string::npos) valid += (valid.empty() ? "" : ", ") + h;
      }
      throw InputError(t.file, "", "no metric column \"" + m + "\"; valid metrics: " + valid);
    }
    c_metric.push_back(c);
  }
  // condition -> label -> seed -> row
  std::map<Condition, std::map<std::string, std::map<std::string, std::size_t>>> runs;
  std::vector<std::string> labels;  // in the sweep's order
  std::set<std::string> seen_labels;
  for (std::size_t i = 0; i < t.rows.size(); ++i) {
    const Condition c{t.text(i, c_scn), t.number(i, c_fpf), t.number(i, c_speed),
                      t.number(i, c_fps)};
    const std::string& label = t.text(i, c_label);
    runs[c][label][t.text(i, c_seed)] = i;
    if (seen_labels.insert(label).second) labels.push_back(label);
  }
  if (!seen_labels.contains(baseline)) {
    std::string valid;
    for (const auto& l : labels) valid += (valid.empty() ? "" : ", ") + l;
    throw InputError(t.file, "",
                     "no planner \"" + baseline + "\" in the sweep; planners: " + valid);
  }
  std::vector<CompareRow> out;
  for (const auto& [cond, by_label] : runs) {
    const auto base = by_label.find(baseline);
    for (const auto& label : labels) {
      const auto it = by_label.find(label);
      if (it == by_label.end()) continue;
      for (std::size_t m = 0; m < metrics.size(); ++m) {
        CompareRow r;
        r.scenario = cond.scenario;
        r.faces_per_frame = cond.faces_per_frame;
        r.speed_scale = cond.speed_scale;
        r.fps = cond.fps;
        r.planner = label;
        r.metric = metrics[m];
        std::vector<double> values, base_values;
        for (const auto& [seed, row] : it->second) {
          const double v = t.number(row, c_metric[m]);
          if (std::isfinite(v)) values.push_back(v);
          if (base == by_label.end()) continue;
          const auto b = base->second.find(seed);
          if (b == base->second.end()) continue;
          const double bv = t.number(b->second, c_metric[m]);
          if (!std::isfinite(v) || !std::isfinite(bv)) continue;
          ++r.paired;
          if (higher_is_better(r.metric) ? v > bv : v < bv) ++r.beats;
        }
        if (base != by_label.end()) {
          for (const auto& [seed, row] : base->second) {
            const double bv = t.number(row, c_metric[m]);
            if (std::isfinite(bv)) base_values.push_back(bv);
          }
        }
        r.seeds = static_cast<int>(values.size());
        r.mean = mean_of(values);
        r.baseline_mean = mean_of(base_values);
        r.ratio = r.baseline_mean != 0.0 ? r.mean / r.baseline_mean : std::nan("");
        std::uint64_t seed = text_hash(0x636F6D70617265ull, cond.scenario);
        seed = text_hash(seed, number(cond.faces_per_frame, 17) + "/" +
                                   number(cond.speed_scale, 17) + "/" + number(cond.fps, 17));
        seed = text_hash(text_hash(seed, label), r.metric);
        r.ci = bootstrap_mean_interval(values, seed);
        out.push_back(std::move(r));
      }
    }
  }
  return out;
}

std::string compare_text(const std::vector<CompareRow>& rows, const std::string& baseline) {
  std::string s;
  std::string heading;
  for (const auto& r : rows) {
    const std::string h = r.scenario + ", " + number(r.faces_per_frame) + " faces/frame, speed x" +
                          number(r.speed_scale) +
                          (r.fps > 0 ? ", " + number(r.fps) + " fps" : std::string());
    if (h != heading) {
      heading = h;
      s += "\n" + h + " (baseline " + baseline + ")\n";
      char line[200];
      std::snprintf(line, sizeof line, "  %-16s %-26s %5s %9s  %-19s %7s %s\n", "planner", "metric",
                    "seeds", "mean", "95% CI", "ratio", "beats baseline");
      s += line;
    }
    char line[240];
    const std::string ci = "[" + fixed(r.ci.low) + ", " + fixed(r.ci.high) + "]";
    std::snprintf(line, sizeof line, "  %-16s %-26s %5d %9s  %-19s %7s %d/%d\n", r.planner.c_str(),
                  r.metric.c_str(), r.seeds, fixed(r.mean).c_str(), ci.c_str(),
                  fixed(r.ratio).c_str(), r.beats, r.paired);
    s += line;
  }
  return s;
}

std::string compare_csv(const std::vector<CompareRow>& rows) {
  std::string s =
      "scenario,faces_per_frame,speed_scale,fps,planner,metric,seeds,mean,ci_low,ci_high,"
      "baseline_mean,ratio,beats,paired\n";
  for (const auto& r : rows) {
    s += r.scenario + "," + number(r.faces_per_frame, 6) + "," + number(r.speed_scale, 6) + "," +
         number(r.fps, 6) + "," + r.planner + "," + r.metric + "," + std::to_string(r.seeds) + "," +
         number(r.mean, 6) + "," + number(r.ci.low, 6) + "," + number(r.ci.high, 6) + "," +
         number(r.baseline_mean, 6) + "," + number(r.ratio, 6) + "," + std::to_string(r.beats) +
         "," + std::to_string(r.paired) + "\n";
  }
  return s;
}

nlohmann::ordered_json compare_json(const std::vector<CompareRow>& rows,
                                    const std::string& baseline) {
  const auto num = [](double x) {
    return std::isfinite(x) ? nlohmann::ordered_json(x) : nlohmann::ordered_json(nullptr);
  };
  nlohmann::ordered_json j;
  j["format"] = "ambisim-compare";
  j["baseline"] = baseline;
  j["confidence"] = "95 % percentile bootstrap over seeds, 10000 resamples";
  nlohmann::ordered_json a = nlohmann::ordered_json::array();
  for (const auto& r : rows) {
    nlohmann::ordered_json e;
    e["scenario"] = r.scenario;
    e["faces_per_frame"] = r.faces_per_frame;
    e["speed_scale"] = r.speed_scale;
    e["fps"] = r.fps;
    e["planner"] = r.planner;
    e["metric"] = r.metric;
    e["seeds"] = r.seeds;
    e["mean"] = num(r.mean);
    e["ci"] = {num(r.ci.low), num(r.ci.high)};
    e["baseline_mean"] = num(r.baseline_mean);
    e["ratio"] = num(r.ratio);
    e["beats"] = r.beats;
    e["paired"] = r.paired;
    a.push_back(std::move(e));
  }
  j["rows"] = std::move(a);
  return j;
}

}  // namespace ambisim
