// `ambisim compare`: replicates grouped by condition, means, ratios and wins against a baseline.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "sim/base/input_error.h"
#include "sim/run/sweep_compare.h"

using namespace ambisim;
namespace fs = std::filesystem;

namespace {

// Two planners x three seeds on one condition, a second condition with one seed; "b" is the
// baseline. p95 of a: 1, 2, 6 (seed 3 worse than b); b: 3, 3, 3. coverage: a 0.5, b 0.2.
CsvTable table() {
  CsvTable t;
  t.file = "summary.csv";
  t.header = {"run",          "scenario", "label", "faces_per_frame",
              "speed_scale",  "fps",      "seed",  "error.viewed.de2000.p95",
              "coverage.mean"};
  const auto row = [&](const char* label, const char* seed, const char* p95, const char* cov,
                       const char* budget = "1") {
    t.rows.push_back({"r", "demo", label, budget, "1", "0", seed, p95, cov});
  };
  row("a", "1", "1", "0.5");
  row("b", "1", "3", "0.2");
  row("a", "2", "2", "0.5");
  row("b", "2", "3", "0.2");
  row("a", "3", "6", "0.5");
  row("b", "3", "3", "0.2");
  row("a", "1", "nan", "0.4", "2");  // nothing to measure there: left out
  row("b", "1", "4", "0.1", "2");
  return t;
}

}  // namespace

TEST_CASE("compare: means, ratios and wins per condition and metric", "[compare]") {
  const auto rows = compare_sweep(table(), "b", {"error.viewed.de2000.p95", "coverage.mean"});
  REQUIRE(rows.size() == 8);  // 2 conditions x 2 planners x 2 metrics
  const CompareRow& a = rows[0];
  CHECK(a.planner == "a");
  CHECK(a.metric == "error.viewed.de2000.p95");
  CHECK(a.faces_per_frame == 1.0);
  CHECK(a.seeds == 3);
  CHECK(a.mean == Approx(3.0));
  CHECK(a.baseline_mean == Approx(3.0));
  CHECK(a.ratio == Approx(1.0));
  CHECK(a.beats == 2);  // seeds 1 and 2: lower is better
  CHECK(a.paired == 3);
  CHECK(a.ci.low >= 1.0);
  CHECK(a.ci.high <= 6.0);
  const CompareRow& cov = rows[1];
  CHECK(cov.metric == "coverage.mean");
  CHECK(cov.beats == 3);  // higher is better for coverage
  CHECK(cov.ratio == Approx(2.5));
  const CompareRow& b = rows[2];
  CHECK(b.planner == "b");
  CHECK(b.beats == 0);
  CHECK(b.ci.low == 3.0);  // all equal: a zero-width interval
  CHECK(b.ci.high == 3.0);
  // The second condition: a's value is NaN, so it has no seed and no pair.
  const CompareRow& a2 = rows[4];
  CHECK(a2.faces_per_frame == 2.0);
  CHECK(a2.seeds == 0);
  CHECK(a2.paired == 0);
  CHECK(std::isnan(a2.mean));
  // Deterministic: the same table gives the same intervals.
  const auto again = compare_sweep(table(), "b", {"error.viewed.de2000.p95", "coverage.mean"});
  CHECK(again[0].ci.low == a.ci.low);
  CHECK(again[0].ci.high == a.ci.high);
  CHECK(compare_csv(rows) == compare_csv(again));
  CHECK(compare_text(rows, "b").find("demo, 1 faces/frame, speed x1 (baseline b)") !=
        std::string::npos);
}

TEST_CASE("compare refuses an unknown baseline or metric, listing the valid ones", "[compare]") {
  try {
    compare_sweep(table(), "c", {"coverage.mean"});
    FAIL("no error");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()) == "summary.csv: no planner \"c\" in the sweep; planners: a, b");
  }
  try {
    compare_sweep(table(), "b", {"coverage.man"});
    FAIL("no error");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("no metric column \"coverage.man\"; valid metrics: "
                                     "error.viewed.de2000.p95, coverage.mean") !=
          std::string::npos);
  }
}
