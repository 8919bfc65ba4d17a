#pragma once
// `ambisim compare`: each planner against a baseline over seeds (SPEC section 5, "Seeds and
// statistics"). From a sweep's summary.csv, runs that differ only in their seed are replicates
// of one condition (scenario, budget, speed scale, frame rate). For each condition, planner and
// metric: the mean over seeds, its 95 % confidence interval (percentile bootstrap, seeded from
// the condition, planner and metric, so the same sweep gives the same interval), the ratio of
// the means to the baseline's, and on how many seeds the planner beats the baseline (seed by
// seed; lower is better, except for coverage). A seed whose value is NaN (nothing to measure,
// e.g. viewed pops when nothing was seen) is left out of that metric.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sim/base/csv_table.h"
#include "sim/base/statistics.h"

namespace ambisim {

// The metrics compared unless others are asked for.
const std::vector<std::string>& default_compare_metrics();

// True where a larger value is better (coverage.*).
bool higher_is_better(const std::string& metric);

struct CompareRow {
  std::string scenario;
  double faces_per_frame = 0.0, speed_scale = 0.0, fps = 0.0;
  std::string planner;  // the run label
  std::string metric;
  int seeds = 0;  // seeds with a value
  double mean = 0.0;
  Interval ci;
  double baseline_mean = 0.0;
  double ratio = 0.0;  // mean / baseline mean (NaN if the baseline mean is 0 or missing)
  int beats = 0;       // seeds on which it beats the baseline (both measured)
  int paired = 0;      // seeds on which both are measured
};

// Throws InputError naming the file for a missing column or an unknown baseline or metric
// (listing the valid ones).
std::vector<CompareRow> compare_sweep(const CsvTable& summary, const std::string& baseline,
                                      const std::vector<std::string>& metrics);

std::string compare_text(const std::vector<CompareRow>& rows, const std::string& baseline);
std::string compare_csv(const std::vector<CompareRow>& rows);
nlohmann::ordered_json compare_json(const std::vector<CompareRow>& rows,
                                    const std::string& baseline);

}  // namespace ambisim
