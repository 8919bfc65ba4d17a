#pragma once
// `ambisim bench-chart`: the PNG chart of docs/PERFORMANCE.md, drawn from the Google Benchmark
// JSON of bench/bench_planners (--benchmark_out=FILE --benchmark_out_format=json). Two panels,
// log-log, one line per planner against the live probes it actually held (the counter
// "live", not the target): lookup cost (BM_Lookup/<planner>/<N>, with the naive linear scan
// BM_LookupNaive/<N> as a dotted grey line) and the planner's per-frame cost
// (BM_Frame/<planner>/<N>).
#include <string>
#include <vector>

#include "sim/base/output_file.h"

namespace ambisim {

// One measured point of bench_planners.
struct PlannerBenchPoint {
  std::string kind;     // "lookup", "lookup_naive" or "frame"
  std::string planner;  // empty for lookup_naive
  double target = 0.0;  // the N asked for
  double live = 0.0;    // live probes actually held
  double ns = 0.0;      // real time per iteration, in nanoseconds
};

// Reads the benchmark entries (iterations, or the median aggregates when repetitions were run).
// Throws InputError naming the file for a missing or invalid file, or one without any
// BM_Lookup / BM_Frame entry.
std::vector<PlannerBenchPoint> read_planner_bench(const std::string& path);

// Writes the chart; InputError as above, or when `png` exists without Overwrite::allow
// (checked before anything is drawn).
void write_planner_bench_chart(const std::string& bench_json, const std::string& png,
                               Overwrite overwrite, int width = 1500, int height = 760);

}  // namespace ambisim
