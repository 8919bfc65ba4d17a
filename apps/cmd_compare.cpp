// `ambisim compare SWEEP_DIR --baseline NAME [--metric M ...] [--csv FILE] [--json FILE]`:
// every planner of a sweep against a baseline over seeds (sim/run/sweep_compare.h): means, 95 %
// bootstrap intervals, ratios and wins, printed as a table; optionally also as CSV and JSON.
#include <cstdio>
#include <filesystem>
#include <memory>

#include "apps/commands.h"
#include "sim/base/input_error.h"
#include "sim/base/output_file.h"
#include "sim/run/sweep_compare.h"

namespace ambisim::cli {
namespace {

struct CompareOptions {
  std::string dir;
  std::string baseline;
  std::vector<std::string> metrics;
  std::string csv, json;
  bool force = false;
};

void run_compare(const CompareOptions& o) {
  namespace fs = std::filesystem;
  if (!fs::is_directory(o.dir)) {
    throw InputError(o.dir, "", "not a directory (expected a sweep output)");
  }
  const Overwrite ow = o.force ? Overwrite::allow : Overwrite::refuse;
  if (!o.csv.empty()) check_output_path(o.csv, ow);
  if (!o.json.empty()) check_output_path(o.json, ow);
  const std::string summary = (fs::path(o.dir) / "summary.csv").string();
  if (!fs::is_regular_file(summary)) {
    throw InputError(summary, "", "missing: not a sweep output directory");
  }
  const auto rows = compare_sweep(read_csv(summary), o.baseline,
                                  o.metrics.empty() ? default_compare_metrics() : o.metrics);
  if (!o.csv.empty()) write_text_atomically(o.csv, compare_csv(rows), ow);
  if (!o.json.empty())
    write_text_atomically(o.json, compare_json(rows, o.baseline).dump(1) + "\n", ow);
  std::fputs(compare_text(rows, o.baseline).c_str(), stdout);
}

}  // namespace

void add_compare_command(CLI::App& app) {
  auto o = std::make_shared<CompareOptions>();
  auto* cmd = app.add_subcommand(
      "compare", "each planner of a sweep against a baseline over seeds (means, 95 % CIs, wins)");
  cmd->add_option("dir", o->dir, "sweep output directory (with summary.csv)")->required();
  cmd->add_option("--baseline", o->baseline, "the planner label compared against")->required();
  cmd->add_option("--metric", o->metrics,
                  "summary column to compare (repeatable; default: viewed and uniform p95 and "
                  "pops, response median, coverage)");
  cmd->add_option("--csv", o->csv, "also write the rows as CSV");
  cmd->add_option("--json", o->json, "also write the rows as JSON");
  cmd->add_flag("--force", o->force, "overwrite existing CSV/JSON outputs");
  cmd->callback([o] { run_compare(*o); });
}

}  // namespace ambisim::cli
