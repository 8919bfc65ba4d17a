// `ambisim plot` on a small synthetic sweep directory: the chart set per scenario, images that
// show something, errors naming the file, no silent overwrite.
#include <algorithm>

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "sim/base/csv_table.h"
#include "sim/base/input_error.h"
#include "tests/viz/image_checks.h"
#include "viz/charts.h"
#include "viz/planner_style.h"
#include "viz/png_writer.h"

namespace fs = std::filesystem;
using nlohmann::json;

using ambisim::test::distinct_colours;

namespace {

// Two planners x three budgets x two speeds on one scenario; one result.json with a series.
fs::path make_sweep_dir() {
  const auto dir = fs::temp_directory_path() / "ambisim_test_charts";
  fs::remove_all(dir);
  fs::create_directories(dir / "runs");
  std::ofstream s(dir / "summary.csv");
  std::ofstream t(dir / "timing.csv");
  s << "run,scenario,planner,label,params,faces_per_frame,speed_scale,fps,seed,scenario_hash,"
       "frames,duration_s,error.viewed.de2000.mean,error.viewed.de2000.p95,pops.viewed.per_min,"
       "coverage.mean\n";
  t << "# measured wall-clock times\n";
  const char* timing_header = "run,timing.note,timing.total_s,timing.planner_us_per_frame\n";
  bool first = true;
  for (const char* planner : {"nearest", "grid"}) {
    for (double budget : {0.5, 1.0, 2.0}) {
      for (double speed : {1.0, 2.0}) {
        const bool grid = planner[0] == 'g';
        const std::string run = std::string("demo__") + planner + "__b" + std::to_string(budget) +
                                "__v" + std::to_string(static_cast<int>(speed));
        const double p95 = (grid ? 6.0 : 9.0) / budget * speed;
        s << run << ",demo," << planner << "," << planner << ",\"{\"\"spacing_m\"\":8}\"," << budget
          << "," << speed << ",0,0,abc,120,2," << p95 / 3 << "," << p95 << ","
          << 10 * speed / budget << "," << (grid ? 0.5 : 0.3) * budget / 2 << "\n";
        t << timing_header << run << ",\"measured, not results\",0.01,"
          << (grid ? 3.0 : 0.5) * budget << "\n";
        if (first) {
          first = false;
          fs::create_directories(dir / "runs" / run);
          json series = {{"time", json::array()},        {"de2000_mean", json::array()},
                         {"de2000_max", json::array()},  {"pops", json::array()},
                         {"live_probes", json::array()}, {"receivers", json::array()},
                         {"coverage", json::array()}};
          for (int f = 0; f < 120; ++f) {
            series["time"].push_back(f / 60.0);
            series["de2000_mean"].push_back(2.0 + std::sin(f * 0.1));
            series["de2000_max"].push_back(f == 0 ? json(nullptr) : json(5.0 + std::sin(f * 0.07)));
            series["pops"].push_back(f % 40 == 7 ? 1 : 0);
            series["live_probes"].push_back(f / 10);
            series["receivers"].push_back(3);
            series["coverage"].push_back(0.01 * (f % 50));
          }
          json result = {
              {"format", "ambisim-run"},
              {"scenario",
               {{"name", "demo"}, {"document", {{"camera", {{"speed_mps", 20.0 * speed}}}}}}},
              {"series", series}};
          std::ofstream(dir / "runs" / run / "result.json") << result.dump();
        }
      }
    }
  }
  return dir;
}

// Pixels of exactly this colour.
std::size_t pixels_of(const ambisim::ImageRgb8& img, const std::array<unsigned char, 3>& c) {
  std::size_t n = 0;
  for (std::size_t i = 0; i + 2 < img.rgb.size(); i += 3) {
    n += img.rgb[i] == c[0] && img.rgb[i + 1] == c[1] && img.rgb[i + 2] == c[2];
  }
  return n;
}

}  // namespace

TEST_CASE("csv reader handles quotes, comments and repeated headers", "[viz][charts]") {
  const auto f = ambisim::split_csv_line(R"(a,"b,""c""",,d)");
  REQUIRE(f.size() == 4);
  CHECK(f[1] == "b,\"c\"");
  CHECK(f[2].empty());
  const auto dir = make_sweep_dir();
  const auto t = ambisim::read_csv((dir / "timing.csv").string());
  CHECK(t.rows.size() == 12);
  CHECK(t.number(0, t.require_column("timing.planner_us_per_frame")) == Approx(0.25));
  CHECK(std::isnan(t.number(0, t.require_column("timing.note"))));
  CHECK_THROWS_AS(t.require_column("nope"), ambisim::InputError);
  fs::remove_all(dir);
}

TEST_CASE("plot writes the chart set per scenario", "[viz][charts]") {
  const auto dir = make_sweep_dir();
  ambisim::PlotOptions opt;
  opt.width = 900;
  opt.height = 600;
  const auto written = ambisim::write_sweep_charts(dir.string(), opt);
  REQUIRE(written.size() == 4);
  for (const char* name : {"demo_accuracy_cost.png", "demo_speed.png", "demo_coverage_budget.png",
                           "demo__nearest__b0.500000__v1_series.png"}) {
    const auto p = dir / "charts" / name;
    REQUIRE(fs::is_regular_file(p));
    const auto img = ambisim::read_png(p.string());
    CHECK(img.width == 900);
    CHECK(img.height == 600);
    CHECK(distinct_colours(img) > 40);
  }
  // Existing charts are kept unless overwriting is allowed.
  CHECK_THROWS_AS(ambisim::write_sweep_charts(dir.string(), opt), ambisim::InputError);
  opt.overwrite = ambisim::Overwrite::allow;
  opt.run_id = "demo__nearest__b0.500000__v1";
  CHECK(ambisim::write_sweep_charts(dir.string(), opt).size() == 4);
  fs::remove_all(dir);
}

TEST_CASE("plot draws box plots across seeds when the sweep has several", "[viz][charts]") {
  const auto dir = fs::temp_directory_path() / "ambisim_test_seed_charts";
  fs::remove_all(dir);
  fs::create_directories(dir / "runs");
  std::ofstream s(dir / "summary.csv");
  s << "run,scenario,planner,label,params,faces_per_frame,speed_scale,fps,seed,scenario_hash,"
       "frames,duration_s,error.viewed.de2000.p95,pops.viewed.per_min,error.uniform.de2000.p95,"
       "pops.uniform.per_min,coverage.mean\n";
  for (const char* planner : {"nearest", "grid", "ambisim"}) {
    for (int seed = 1; seed <= 5; ++seed) {
      const double p95 = (planner[0] == 'a' ? 1.0 : 4.0) + 0.3 * seed;
      s << "demo__" << planner << "__s" << seed << ",demo," << planner << "," << planner
        << ",{},1,1,0," << seed << ",abc,120,2," << p95 << "," << 2.0 * seed << "," << 2.0 * p95
        << "," << seed << ",0.5\n";
    }
  }
  s.close();
  fs::create_directories(dir / "runs" / "demo__ambisim__s1");
  std::ofstream(dir / "runs" / "demo__ambisim__s1" / "result.json")
      << R"({"series": {"time": [0, 1, 2], "de2000_mean": [1, 2, 1], "pops": [0, 1, 0]}})";
  ambisim::PlotOptions opt;
  opt.width = 900;
  opt.height = 600;
  opt.run_id = "demo__ambisim__s1";
  const auto written = ambisim::write_sweep_charts(dir.string(), opt);
  const auto boxes = dir / "charts" / "demo_seeds.png";
  REQUIRE(std::find(written.begin(), written.end(), boxes.string()) != written.end());
  const auto img = ambisim::read_png(boxes.string());
  CHECK(img.width == 900);
  CHECK(img.height == 780);  // taller, for the planner names under the boxes
  CHECK(distinct_colours(img) > 40);
  fs::remove_all(dir);
}

TEST_CASE("plot rejects bad input naming the file", "[viz][charts]") {
  const auto dir = make_sweep_dir();
  ambisim::PlotOptions opt;
  opt.run_id = "no_such_run";
  try {
    ambisim::write_sweep_charts(dir.string(), opt);
    FAIL("no error for an unknown run");
  } catch (const ambisim::InputError& e) {
    CHECK(std::string(e.what()).find("summary.csv") != std::string::npos);
    CHECK(std::string(e.what()).find("no_such_run") != std::string::npos);
  }
  CHECK_FALSE(fs::exists(dir / "charts"));
  opt.run_id.clear();
  fs::remove(dir / "summary.csv");
  try {
    ambisim::write_sweep_charts(dir.string(), opt);
    FAIL("no error for a missing summary.csv");
  } catch (const ambisim::InputError& e) {
    CHECK(std::string(e.what()).find("summary.csv") != std::string::npos);
  }
  CHECK_THROWS_AS(ambisim::write_sweep_charts((dir / "missing").string(), opt),
                  ambisim::InputError);
  fs::remove_all(dir);
}

TEST_CASE("axes fit the data: small margins, no room for a legend drawn outside", "[viz][charts]") {
  ambisim::ChartPanel p;
  for (int k = 0; k < 14; ++k) {
    ambisim::ChartSeries s;
    s.name = "planner " + std::to_string(k);
    s.x = {30.0, 60.0};
    s.y = {2.0 + k, 27.0 - k};
    p.series.push_back(s);
  }
  auto r = ambisim::panel_ranges(p);
  CHECK(r.y[0] == 0.0);
  CHECK(r.y[1] >= 27.0);
  CHECK(r.y[1] <= 27.0 * 1.05);
  CHECK(r.x[0] < 30.0);
  CHECK(r.x[0] > 28.0);
  CHECK(r.x[1] > 60.0);
  CHECK(r.x[1] < 62.0);
  // An inline legend over a third of the plot: the y axis grows by that much, no more.
  r = ambisim::panel_ranges(p, 1.0 / 3.0);
  CHECK(r.y[1] == Approx(27.0 * 1.04 * 1.5));
  // Log axes: a margin in decades; not from zero.
  p.log_x = p.log_y = true;
  p.series[0].x = {0.1, 100.0};
  r = ambisim::panel_ranges(p);
  CHECK(r.x[0] < 0.1);
  CHECK(r.x[0] > 0.1 / 1.5);
  CHECK(r.x[1] > 100.0);
  CHECK(r.x[1] < 150.0);
  CHECK(r.y[0] > 1.0);
  CHECK(r.y[1] < 27.0 * 1.5);
}

TEST_CASE("plot draws every planner of a 20-planner sweep in its own style", "[viz][charts]") {
  const auto dir = fs::temp_directory_path() / "ambisim_test_styled_charts";
  fs::remove_all(dir);
  fs::create_directories(dir / "runs");
  std::vector<std::string> planners = {
      "oracle",    "constant", "hemisphere", "nearest",       "per_object", "grid",   "octree",
      "octree+vp", "shgraph",  "shgraph+vp", "shgraph+route", "shgraph2d",  "ambisim"};
  for (int k = 1; k <= 7; ++k) planners.push_back("new_planner_" + std::to_string(k));
  std::ofstream s(dir / "summary.csv");
  std::ofstream t(dir / "timing.csv");
  s << "run,scenario,planner,label,params,faces_per_frame,speed_scale,fps,seed,scenario_hash,"
       "frames,duration_s,error.viewed.de2000.p95,pops.viewed.per_min,error.uniform.de2000.p95,"
       "pops.uniform.per_min,coverage.mean,memory.max_bytes\n";
  t << "run,timing.planner_us_per_frame\n";
  std::string first;
  for (std::size_t k = 0; k < planners.size(); ++k) {
    for (double budget : {0.5, 1.0, 2.0}) {
      for (double speed : {1.0, 2.0}) {
        for (int seed = 1; seed <= 3; ++seed) {
          const std::string run = "demo__" + planners[k] + "__b" + std::to_string(budget) + "__v" +
                                  std::to_string(speed) + "__s" + std::to_string(seed);
          if (first.empty()) first = run;
          const double p95 =
              (1.0 + static_cast<double>(k)) * (1.0 + 0.5 / budget) * speed + 0.1 * seed;
          s << run << ",demo," << planners[k] << "," << planners[k] << ",{}," << budget << ","
            << speed << ",60," << seed << ",abc,120,2," << p95 << "," << 3 * p95 << "," << 2 * p95
            << "," << 4 * p95 << "," << 0.02 * static_cast<double>(k) * budget << ","
            << 300 * std::pow(1.5, static_cast<double>(k)) << "\n";
          t << run << "," << 0.1 * std::pow(1.4, static_cast<double>(k)) * budget << "\n";
        }
      }
    }
  }
  s.close();
  t.close();
  fs::create_directories(dir / "runs" / first);
  std::ofstream(dir / "runs" / first / "result.json")
      << R"({"series": {"time": [0, 1, 2], "de2000_mean": [1, 2, 1], "pops": [0, 1, 0]}})";
  ambisim::PlotOptions opt;
  const auto written = ambisim::write_sweep_charts(dir.string(), opt);
  CHECK(written.size() == 5);
  const auto styles = ambisim::planner_styles(planners);
  // Twenty planners, twenty colours: each one shows in every chart of planners (the box plots
  // have no legend: there only the boxes and dots carry the colours).
  for (const char* chart : {"demo_accuracy_cost.png", "demo_speed.png", "demo_seeds.png"}) {
    const auto img = ambisim::read_png((dir / "charts" / chart).string());
    for (const auto& [label, st] : styles) {
      INFO(chart << ": " << label);
      CHECK(pixels_of(img, st.rgb) >= 20);
    }
  }
  fs::remove_all(dir);
}

TEST_CASE("plot draws error over the time of day for light that changes", "[viz][charts]") {
  // The time axis: a sun on the solar path from 06:30 at 360x gives the local time in hours.
  const json solar = {
      {"scenario",
       {{"document",
         {{"world",
           {{"sun",
             {{"path", {{"type", "solar"}, {"start", "06:30"}, {"time_scale", 360}}}}}}}}}}}};
  const auto a = ambisim::light_time_axis(solar);
  CHECK(a.start + a.scale * 10.0 == Approx(7.5));  // 10 s x 360 = 1 h
  CHECK(a.label == "local time of day (h)");
  CHECK(ambisim::scenario_light_changes(solar));
  const json keyed = {
      {"scenario", {{"document", {{"world", {{"sun", {{"path", {{"type", "keyframes"}}}}}}}}}}}};
  CHECK(ambisim::light_time_axis(keyed).start + ambisim::light_time_axis(keyed).scale * 10.0 ==
        Approx(10.0));
  const json fog = {{"scenario", {{"document", {{"world", {{"fog", {{"colour", {1, 1, 1}}}}}}}}}}};
  const json fog_off = {{"scenario", {{"document", {{"world", {{"fog", {{"enabled", false}}}}}}}}}};
  const json fixed = {
      {"scenario", {{"document", {{"world", {{"sun", {{"elevation_deg", 30}}}}}}}}}};
  CHECK(ambisim::scenario_light_changes(fog));
  CHECK_FALSE(ambisim::scenario_light_changes(fog_off));
  CHECK_FALSE(ambisim::scenario_light_changes(fixed));

  // A sweep of a day: the chart is drawn for it, not for a sweep whose light is fixed.
  const auto dir = fs::temp_directory_path() / "ambisim_test_light_charts";
  fs::remove_all(dir);
  fs::create_directories(dir / "runs");
  std::ofstream s(dir / "summary.csv");
  s << "run,scenario,planner,label,params,faces_per_frame,speed_scale,fps,seed,scenario_hash,"
       "frames,duration_s,error.viewed.de2000.p95,pops.viewed.per_min,coverage.mean\n";
  for (const char* planner : {"baked", "ambisim"}) {
    for (int seed = 1; seed <= 2; ++seed) {
      const std::string run = std::string("day__") + planner + "__s" + std::to_string(seed);
      s << run << ",day," << planner << "," << planner << ",{},1,1,0," << seed
        << ",abc,120,20,1,0,0.5\n";
      json series = {{"time", json::array()},
                     {"de2000_mean", json::array()},
                     {"de2000_viewed_mean", json::array()}};
      for (int f = 0; f < 200; ++f) {
        series["time"].push_back(f * 0.1);
        const double e = planner[0] == 'b' ? 0.5 * f * 0.1 : 1.0 + 0.1 * seed;
        series["de2000_mean"].push_back(e);
        series["de2000_viewed_mean"].push_back(0.5 * e);
      }
      fs::create_directories(dir / "runs" / run);
      json result = solar;
      result["series"] = series;
      std::ofstream(dir / "runs" / run / "result.json") << result.dump();
    }
  }
  s.close();
  ambisim::PlotOptions opt;
  opt.width = 900;
  opt.height = 600;
  const auto written = ambisim::write_sweep_charts(dir.string(), opt);
  const auto light = dir / "charts" / "day_light.png";
  REQUIRE(std::find(written.begin(), written.end(), light.string()) != written.end());
  const auto img = ambisim::read_png(light.string());
  CHECK(distinct_colours(img) > 40);
  const auto ours = ambisim::known_planner_style("ambisim");
  REQUIRE(ours.has_value());
  CHECK(pixels_of(img, ours->rgb) > 100);
  fs::remove_all(dir);

  const auto plain = make_sweep_dir();
  for (const auto& p : ambisim::write_sweep_charts(plain.string(), opt)) {
    CHECK(p.find("_light.png") == std::string::npos);
  }
  fs::remove_all(plain);
}
