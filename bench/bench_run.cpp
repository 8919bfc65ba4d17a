// Whole-run throughput on scenarios/motorway.json (60 s at 60 fps = 3600 frames, 24 vehicles
// live, 1 face per frame, 16x16 captures): simulated frames per second and multiples of real
// time, per planner, with the reference off (simulate_without_reference: everything the
// planner does, captures rendered, nothing scored) and on (simulate against the reference
// track, which a sweep computes once per scenario variant and shares). The one-off costs of a
// single `ambisim run` are measured apart: world generation and the reference track.
//
//   build/bench/bench_run --benchmark_out=run.json --benchmark_out_format=json
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

// One scenario of the benchmarks: its record, its world (built on first use) and its reference
// track (computed by the benchmark that times it, or by the first run that needs it).
struct BenchScene {
  explicit BenchScene(const char* file)
      : scenario(load_scenario(std::string(AMBISIM_SOURCE_DIR) + "/scenarios/" + file)) {}
  const World& world() {
    if (!world_) world_ = std::make_unique<const World>(scenario.world);
    return *world_;
  }
  const ReferenceTrack& reference() {
    if (!track) track = compute_reference_track(scenario, world());
    return *track;
  }
  Scenario scenario;
  std::shared_ptr<const ReferenceTrack> track;

 private:
  std::unique_ptr<const World> world_;
};

BenchScene& motorway() {
  static BenchScene s("motorway.json");
  return s;
}

BenchScene& rush_hour() {
  static BenchScene s("rush_hour.json");
  return s;
}

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
  BenchScene& scene = motorway();
  // Built before the timed loop: the first planner to run must not pay for the world.
  const World& world = scene.world();
  for (auto _ : state) {
    auto p = make_planner(planner);
    const RunResult r = simulate_without_reference(scene.scenario, world, *p);
    report(state, r, r.timing.total_s);
  }
}

// A run scored against the scene's reference (computed before the timed loop). Both
// BM_RunReferenceOn (motorway) and BM_RushHourRun (rush_hour's third part, see the top).
void BM_RunWithReference(benchmark::State& state, BenchScene* scene, const std::string& planner) {
  const World& world = scene->world();
  const ReferenceTrack& ref = scene->reference();
  for (auto _ : state) {
    auto p = make_planner(planner);
    const RunResult r = simulate(scene->scenario, world, ref, *p);
    report(state, r, r.timing.total_s);
    state.counters["lookups"] = static_cast<double>(r.timing.lookups);
  }
}

// The one-off parts of `ambisim run`: the world and the reference track.
void BM_World(benchmark::State& state, BenchScene* scene) {
  for (auto _ : state) {
    World w{scene->scenario.world};
    benchmark::DoNotOptimize(w.max_surface());
  }
}

void BM_Reference(benchmark::State& state, BenchScene* scene) {
  const World& w = scene->world();
  for (auto _ : state) {
    scene->track = compute_reference_track(scene->scenario, w);
    state.counters["captures"] = static_cast<double>(scene->track->captures);
    state.counters["slots"] = static_cast<double>(scene->track->ids.size());
    state.counters["interpolated"] = static_cast<double>(scene->track->slots_interpolated);
  }
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RegisterBenchmark("BM_MotorwayWorld", BM_World, &motorway())
      ->Iterations(1)
      ->Unit(benchmark::kMillisecond);
  for (const auto& info : planner_catalogue()) {
    if (info.name == "oracle") continue;  // served from the reference: no "off" run
    benchmark::RegisterBenchmark(("BM_RunReferenceOff/" + info.name).c_str(), BM_RunReferenceOff,
                                 info.name)
        ->Iterations(1)
        ->Unit(benchmark::kMillisecond);
  }
  benchmark::RegisterBenchmark("BM_MotorwayReference", BM_Reference, &motorway())
      ->Iterations(1)
      ->Unit(benchmark::kMillisecond);
  for (const auto& info : planner_catalogue()) {
    benchmark::RegisterBenchmark(("BM_RunReferenceOn/" + info.name).c_str(), BM_RunWithReference,
                                 &motorway(), info.name)
        ->Iterations(1)
        ->Unit(benchmark::kMillisecond);
  }
  benchmark::RegisterBenchmark("BM_RushHourWorld", BM_World, &rush_hour())
      ->Iterations(1)
      ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("BM_RushHourReference", BM_Reference, &rush_hour())
      ->Iterations(1)
      ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("BM_RushHourRun/ambisim", BM_RunWithReference, &rush_hour(),
                               std::string("ambisim"))
      ->Iterations(1)
      ->Unit(benchmark::kMillisecond);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
