// `ambisim bench-chart`: Google Benchmark JSON of bench_planners in, a log-log chart out; the
// points are the live probes actually held, medians when repetitions were run.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <set>

#include <nlohmann/json.hpp>

#include "sim/base/input_error.h"
#include "viz/bench_chart.h"
#include "viz/png_writer.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

json entry(const std::string& run, double time, const char* unit, double live,
           const char* type = "iteration", const char* aggregate = "") {
  json e = {{"name", run},      {"run_name", run},   {"run_type", type}, {"real_time", time},
            {"cpu_time", time}, {"time_unit", unit}, {"live", live}};
  if (*aggregate) {
    e["aggregate_name"] = aggregate;
    e["name"] = run + "_" + aggregate;
  }
  return e;
}

fs::path write_json(const std::string& name, const json& j) {
  const auto p = fs::temp_directory_path() / name;
  std::ofstream(p) << j.dump(1);
  return p;
}

json sample() {
  json b = json::array();
  for (const char* planner : {"shgraph", "nearest+x"}) {
    for (double n : {1000.0, 10000.0, 100000.0}) {
      const std::string p = planner;
      b.push_back(entry("BM_Lookup/" + p + "/" + std::to_string(static_cast<int>(n)),
                        p == "shgraph" ? 100.0 : n / 10.0, "ns", n * 0.9));
      if (n < 1e5) {
        b.push_back(
            entry("BM_Frame/" + p + "/" + std::to_string(static_cast<int>(n)) + "/iterations:600",
                  n / 100.0, "us", n));
      }
    }
  }
  b.push_back(entry("BM_LookupNaive/1000", 900.0, "ns", 1000.0));
  b.push_back(entry("BM_LookupNaive/100000", 90000.0, "ns", 100000.0));
  b.push_back(entry("BM_Other", 1.0, "ns", 0.0));
  return {{"context", {{"num_cpus", 2}}}, {"benchmarks", b}};
}

}  // namespace

TEST_CASE("bench-chart reads bench_planners JSON: kinds, planners, live probes, units",
          "[bench_chart]") {
  const auto pts =
      ambisim::read_planner_bench(write_json("ambisim_bench_a.json", sample()).string());
  CHECK(pts.size() == 6 + 4 + 2);
  int lookups = 0, frames = 0, naive = 0;
  for (const auto& p : pts) {
    if (p.kind == "lookup") ++lookups;
    if (p.kind == "frame") {
      ++frames;
      // "us" converted to ns; the /iterations:600 suffix ignored.
      if (p.planner == "shgraph" && p.target == 1000.0) CHECK(p.ns == Approx(10.0 * 1e3));
    }
    if (p.kind == "lookup_naive") ++naive;
    if (p.kind == "lookup" && p.planner == "shgraph" && p.target == 1000.0) {
      CHECK(p.live == 900.0);  // the count reached, not the target
    }
  }
  CHECK(lookups == 6);
  CHECK(frames == 4);
  CHECK(naive == 2);
}

TEST_CASE("bench-chart prefers medians when repetitions were run", "[bench_chart]") {
  json b = json::array();
  b.push_back(entry("BM_Lookup/grid/1000", 50.0, "ns", 1000.0));
  b.push_back(entry("BM_Lookup/grid/1000", 70.0, "ns", 1000.0));
  b.push_back(entry("BM_Lookup/grid/1000", 60.0, "ns", 1000.0, "aggregate", "median"));
  b.push_back(entry("BM_Lookup/grid/1000", 62.0, "ns", 1000.0, "aggregate", "mean"));
  const auto pts =
      ambisim::read_planner_bench(write_json("ambisim_bench_b.json", {{"benchmarks", b}}).string());
  REQUIRE(pts.size() == 1);
  CHECK(pts[0].ns == 60.0);
}

TEST_CASE("bench-chart reads Google Benchmark's NaN spreads", "[bench_chart]") {
  const auto p = fs::temp_directory_path() / "ambisim_bench_nan.json";
  std::ofstream(p) << R"({"benchmarks": [
    {"name": "BM_Lookup/grid/1000_median", "run_name": "BM_Lookup/grid/1000",
     "run_type": "aggregate", "aggregate_name": "median", "real_time": 60, "time_unit": "ns",
     "live": 1000, "fell_back": 0},
    {"name": "BM_Lookup/grid/1000_cv", "run_name": "BM_Lookup/grid/1000",
     "run_type": "aggregate", "aggregate_name": "cv", "real_time": 0.01, "time_unit": "ns",
     "live": 0, "fell_back": NaN, "nodes": -inf}]})";
  const auto pts = ambisim::read_planner_bench(p.string());
  REQUIRE(pts.size() == 1);
  CHECK(pts[0].ns == 60.0);
}

TEST_CASE("bench-chart draws a non-blank PNG and refuses to overwrite it", "[bench_chart]") {
  const auto in = write_json("ambisim_bench_c.json", sample());
  const auto png = fs::temp_directory_path() / "ambisim_bench_chart.png";
  fs::remove(png);
  ambisim::write_planner_bench_chart(in.string(), png.string(), ambisim::Overwrite::refuse);
  const auto img = ambisim::read_png(png.string());
  CHECK(img.width == 1500);
  std::set<std::uint32_t> colours;
  for (std::size_t i = 0; i + 2 < img.rgb.size(); i += 3) {
    colours.insert((std::uint32_t(img.rgb[i]) << 16) | (std::uint32_t(img.rgb[i + 1]) << 8) |
                   img.rgb[i + 2]);
  }
  CHECK(colours.size() > 40);
  CHECK_THROWS_AS(
      ambisim::write_planner_bench_chart(in.string(), png.string(), ambisim::Overwrite::refuse),
      ambisim::InputError);
  fs::remove(png);
}

TEST_CASE("bench-chart input errors name the file", "[bench_chart]") {
  const auto png = (fs::temp_directory_path() / "ambisim_bench_never.png").string();
  CHECK_THROWS_WITH(ambisim::read_planner_bench("/nonexistent/bench.json"),
                    Catch::Contains("/nonexistent/bench.json"));
  const auto not_bench = write_json("ambisim_bench_d.json", {{"format", "ambisim-run"}});
  CHECK_THROWS_WITH(ambisim::read_planner_bench(not_bench.string()),
                    Catch::Contains("not Google Benchmark JSON"));
  json b = json::array();
  b.push_back(entry("BM_Capture16/0/0", 1.0, "ms", 0.0));
  const auto other = write_json("ambisim_bench_e.json", {{"benchmarks", b}});
  CHECK_THROWS_WITH(
      ambisim::write_planner_bench_chart(other.string(), png, ambisim::Overwrite::refuse),
      Catch::Contains("no BM_Lookup or BM_Frame"));
  CHECK_FALSE(fs::exists(png));
}
