// Whole-run throughput on scenarios/motorway.json (60 s at 60 fps = 3600 frames, 24 vehicles
// live, 1 face per frame, 16x16 captures): simulated frames per second and multiples of real
// time, per planner, with the reference off (simulate_without_reference: everything the
// planner does, captures rendered, nothing scored) and on (simulate against the reference
// track, which a sweep computes once per scenario variant and shares). The one-off costs of a
// single `ambisim run` are measured apart: world generation and the reference track.
//
//   build-perf/bench/bench_run --benchmark_out=run.json --benchmark_out_format=json
//
// The game's-load target (SPEC section 8): a 60 s rush_hour run with its reference in at most
// 60 s of CPU on one core. BM_RushHourWorld, BM_RushHourReference and BM_RushHourRun/ambisim
// are the three parts of a single `ambisim run scenarios/rush_hour.json --planner ambisim`;
// their CPU times add up to the run's (scripts/perf_runs.py sums them).
//
// Every benchmark runs exactly once (Iterations(1)): a run is seconds long and deterministic.
// Counters: frames, sim_s (simulated seconds), fps (simulated frames per wall second),
// realtime_x (simulated seconds per wall second), planner_us (plan + update + deliver per
// frame), lookup_ns (per planner lookup), capture_ms (rendering + projection, whole run),
// bake_s (the baked planners' preload before the first frame, part of the wall time).
#include <benchmark/benchmark.h>

#include <memory>
#include <string>

#include "policies/registry/registry.h"
#include "sim/run/reference_track.h"
#include "sim/run/simulator.h"
#include "sim/scenario/scenario.h"
#include "sim/world/world.h"

using namespace ambisim;

namespace {

const Scenario& motorway() {
  static const Scenario s =
      load_scenario(std::string(AMBISIM_SOURCE_DIR) + "/scenarios/motorway.json");
  return s;
}

const World& motorway_world() {
  static const World w{motorway().world};
  return w;
}

// Computed once: by BM_MotorwayReference (which times it) or by the first run that needs it.
std::shared_ptr<const ReferenceTrack> g_reference;

const ReferenceTrack& motorway_reference() {
  if (!g_reference) g_reference = compute_reference_track(motorway(), motorway_world());
  return *g_reference;
}

const Scenario& rush_hour() {
  static const Scenario s =
      load_scenario(std::string(AMBISIM_SOURCE_DIR) + "/scenarios/rush_hour.json");
  return s;
}

const World& rush_hour_world() {
  static const World w{rush_hour().world};
  return w;
}

std::shared_ptr<const ReferenceTrack> g_rush_hour_reference;

void report(benchmark::State& state, const RunResult& r, double wall_s) {
  const double sim_s = r.summary.duration_s;
  const auto frames = static_cast<double>(r.timing.frames);
  state.counters["frames"] = frames;
  state.counters["sim_s"] = sim_s;
  state.counters["fps"] = frames / wall_s;
  state.counters["realtime_x"] = sim_s / wall_s;
  state.counters["planner_us"] = frames > 0 ? 1e6 * r.timing.planner_s / frames : 0.0;
  state.counters["lookup_ns"] =
      r.timing.lookups > 0 ? 1e9 * r.timing.lookup_s / static_cast<double>(r.timing.lookups) : 0.0;
  state.counters["capture_ms"] = 1e3 * r.timing.capture_s;
  // The baked planners' preload (offline work a studio does once), inside the wall time.
  state.counters["bake_s"] = r.timing.bake_s;
}

void BM_RunReferenceOff(benchmark::State& state, const std::string& planner) {
  const World& w = motorway_world();
  for (auto _ : state) {
    auto p = make_planner(planner);
    const RunResult r = simulate_without_reference(motorway(), w, *p);
    report(state, r, r.timing.total_s);
  }
}

void BM_RunReferenceOn(benchmark::State& state, const std::string& planner) {
  const World& w = motorway_world();
  const ReferenceTrack& ref = motorway_reference();
  for (auto _ : state) {
    auto p = make_planner(planner);
    const RunResult r = simulate(motorway(), w, ref, *p);
    report(state, r, r.timing.total_s);
  }
}

// The one-off parts of `ambisim run`: the world and the reference track.
void BM_MotorwayWorld(benchmark::State& state) {
  for (auto _ : state) {
    World w{motorway().world};
    benchmark::DoNotOptimize(w.max_surface());
  }
}

void BM_MotorwayReference(benchmark::State& state) {
  const World& w = motorway_world();
  for (auto _ : state) {
    g_reference = compute_reference_track(motorway(), w);
    state.counters["captures"] = static_cast<double>(g_reference->captures);
  }
}

// The rush_hour run's three parts, each timed on its own (see the top of this file).
void BM_RushHourWorld(benchmark::State& state) {
  for (auto _ : state) {
    World w{rush_hour().world};
    benchmark::DoNotOptimize(w.max_surface());
  }
}

void BM_RushHourReference(benchmark::State& state) {
  const World& w = rush_hour_world();
  for (auto _ : state) {
    g_rush_hour_reference = compute_reference_track(rush_hour(), w);
    state.counters["captures"] = static_cast<double>(g_rush_hour_reference->captures);
    state.counters["slots"] = static_cast<double>(g_rush_hour_reference->ids.size());
    state.counters["interpolated"] = static_cast<double>(g_rush_hour_reference->slots_interpolated);
  }
}

void BM_RushHourRun(benchmark::State& state, const std::string& planner) {
  const World& w = rush_hour_world();
  if (!g_rush_hour_reference) g_rush_hour_reference = compute_reference_track(rush_hour(), w);
  for (auto _ : state) {
    auto p = make_planner(planner);
    const RunResult r = simulate(rush_hour(), w, *g_rush_hour_reference, *p);
    report(state, r, r.timing.total_s);
    state.counters["lookups"] = static_cast<double>(r.timing.lookups);
  }
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RegisterBenchmark("BM_MotorwayWorld", BM_MotorwayWorld)
      ->Iterations(1)
      ->Unit(benchmark::kMillisecond);
  for (const auto& info : planner_catalogue()) {
    if (info.name == "oracle") continue;  // served from the reference: no "off" run
    benchmark::RegisterBenchmark(("BM_RunReferenceOff/" + info.name).c_str(), BM_RunReferenceOff,
                                 info.name)
        ->Iterations(1)
        ->Unit(benchmark::kMillisecond);
  }
  benchmark::RegisterBenchmark("BM_MotorwayReference", BM_MotorwayReference)
      ->Iterations(1)
      ->Unit(benchmark::kMillisecond);
  for (const auto& info : planner_catalogue()) {
    benchmark::RegisterBenchmark(("BM_RunReferenceOn/" + info.name).c_str(), BM_RunReferenceOn,
                                 info.name)
        ->Iterations(1)
        ->Unit(benchmark::kMillisecond);
  }
  benchmark::RegisterBenchmark("BM_RushHourWorld", BM_RushHourWorld)
      ->Iterations(1)
      ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("BM_RushHourReference", BM_RushHourReference)
      ->Iterations(1)
      ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("BM_RushHourRun/ambisim", BM_RushHourRun, std::string("ambisim"))
      ->Iterations(1)
      ->Unit(benchmark::kMillisecond);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
