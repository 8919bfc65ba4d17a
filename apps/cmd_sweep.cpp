// `ambisim sweep SWEEP.json --out DIR [-j N] [--shard K/N] [--resume] [--force]`.
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <memory>
#include <thread>

#include "apps/commands.h"
#include "policies/registry/registry.h"
#include "sim/base/input_error.h"
#include "sim/run/sweep.h"

namespace ambisim::cli {
namespace {

std::atomic<bool> g_stop{false};
extern "C" void on_sigint(int) { g_stop.store(true); }

struct SweepCliOptions {
  std::string sweep;
  std::string out;
  int jobs = 0;
  std::string shard = "1/1";
  bool resume = false;
  bool force = false;
};

std::string eta_text(double s) {
  char buf[32];
  if (s >= 3600) {
    std::snprintf(buf, sizeof buf, "%dh%02dm", static_cast<int>(s / 3600),
                  static_cast<int>(s / 60) % 60);
  } else {
    std::snprintf(buf, sizeof buf, "%dm%02ds", static_cast<int>(s / 60), static_cast<int>(s) % 60);
  }
  return buf;
}

void run_sweep_command(const SweepCliOptions& o) {
  int k = 0, n = 0;
  char tail = 0;
  if (std::sscanf(o.shard.c_str(), "%d/%d%c", &k, &n, &tail) != 2 || n < 1 || k < 1 || k > n) {
    throw InputError("--shard", "", "expects K/N with 1 <= K <= N, got " + o.shard);
  }
  const SweepSpec spec = load_sweep(o.sweep);
  // Planner names first, at their own JSON path, before any scenario variant is parsed.
  for (const auto& p : spec.planners) {
    const std::string at = p.params_pointer.substr(0, p.params_pointer.rfind('/'));
    (void)find_planner(p.name, spec.file, at);
  }
  SweepOptions opt;
  opt.jobs =
      o.jobs > 0 ? o.jobs : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  opt.shard_index = k - 1;
  opt.shard_count = n;
  opt.resume = o.resume;
  opt.force = o.force;
  opt.stop = &g_stop;
  const bool tty = ::isatty(STDERR_FILENO) != 0;
  opt.progress = [tty](std::size_t done, std::size_t total, double eta, const std::string& id) {
    if (tty) {
      const int width = 30;
      const int filled = total ? static_cast<int>(width * done / total) : width;
      std::fprintf(stderr, "\r[%s%s] %zu/%zu ETA %s  %-60.60s", std::string(filled, '#').c_str(),
                   std::string(width - filled, '.').c_str(), done, total, eta_text(eta).c_str(),
                   id.c_str());
      if (done == total) std::fprintf(stderr, "\n");
    } else {
      std::fprintf(stderr, "sweep: %zu/%zu done, ETA %s, finished %s\n", done, total,
                   eta_text(eta).c_str(), id.c_str());
    }
  };
  std::signal(SIGINT, on_sigint);
  const PlannerFactory factory = [&spec](const SweepPlanner& p) {
    return make_planner(
        p.name, planner_params_from_json(p.name, p.params, spec.file, p.params_pointer, p.preset,
                                         p.preset_pointer));
  };
  const SweepReport report = run_sweep(spec, o.out, factory, opt);
  std::signal(SIGINT, SIG_DFL);
  std::fprintf(stderr, "sweep %s: %zu runs in this shard, %zu run, %zu resumed%s -> %s\n",
               spec.name.c_str(), report.total, report.executed, report.skipped,
               report.interrupted ? ", INTERRUPTED (rerun with --resume)" : "", o.out.c_str());
  if (report.interrupted) throw InputError(o.sweep, "", "interrupted");
}

}  // namespace

void add_sweep_command(CLI::App& app) {
  auto o = std::make_shared<SweepCliOptions>();
  auto* cmd = app.add_subcommand("sweep", "run scenarios x planners x budgets x speeds x fps");
  cmd->add_option("sweep", o->sweep, "sweep JSON file")->required();
  cmd->add_option("--out", o->out, "output directory")->required();
  cmd->add_option("-j,--jobs", o->jobs, "parallel runs (default: all cores)")
      ->check(CLI::Range(1, 256));
  cmd->add_option("--shard", o->shard, "run only shard K of N (K/N, 1-based)");
  cmd->add_flag("--resume", o->resume, "skip runs whose result exists and matches");
  cmd->add_flag("--force", o->force, "overwrite existing results");
  cmd->callback([o] { run_sweep_command(*o); });
}

}  // namespace ambisim::cli
