// simulate_without_reference ("reference off", used by the throughput benchmark): every planner
// sees and does exactly what it does in a scored run; only the scoring against truth is gone.
#include <catch2/catch.hpp>

#include <cmath>
#include <stdexcept>

#include "policies/registry/registry.h"
#include "sim/run/reference_track.h"
#include "sim/run/simulator.h"
#include "sim/scenario/scenario.h"
#include "sim/world/world.h"
#include "tests/support/scenario_fixtures.h"

using namespace ambisim;

namespace {

test::SmallDrive& small_drive() {
  static test::SmallDrive f;
  return f;
}

}  // namespace

TEST_CASE("without a reference every planner plans, captures and serves exactly as with it",
          "[simulation]") {
  auto& f = small_drive();
  for (const auto& info : planner_catalogue()) {
    if (info.name == "oracle") continue;  // served from the reference (next test)
    INFO(info.name);
    auto with_planner = test::make_test_planner(info.name);
    auto without_planner = test::make_test_planner(info.name);
    const RunResult with = simulate(f.scenario, f.world, *f.reference, *with_planner);
    const RunResult without = simulate_without_reference(f.scenario, f.world, *without_planner);

    // Planner-facing results: identical.
    CHECK(without.captures_started == with.captures_started);
    CHECK(without.captures_delivered == with.captures_delivered);
    const Summary& a = with.summary;
    const Summary& b = without.summary;
    CHECK(b.frames == a.frames);
    CHECK(b.faces.requested == a.faces.requested);
    CHECK(b.faces.granted == a.faces.granted);
    CHECK(b.faces.used == a.faces.used);
    CHECK(b.faces.refused == a.faces.refused);
    CHECK(b.captures_refused == a.captures_refused);
    CHECK(b.probes.max_live == a.probes.max_live);
    CHECK(b.probes.mean_live == a.probes.mean_live);
    CHECK(b.memory.max_bytes == a.memory.max_bytes);
    CHECK(b.memory.mean_bytes == a.memory.mean_bytes);
    CHECK(b.coverage.mean == a.coverage.mean);
    CHECK(b.coverage.receivers == a.coverage.receivers);
    CHECK(b.coverage.ground == a.coverage.ground);
    CHECK(b.coverage.samples == a.coverage.samples);
    CHECK(without.timing.lookups == with.timing.lookups);
    REQUIRE(without.frames.size() == with.frames.size());
    for (std::size_t i = 0; i < with.frames.size(); ++i) {
      const FrameRow& x = with.frames[i];
      const FrameRow& y = without.frames[i];
      INFO("frame " << i);
      REQUIRE(y.faces_granted == x.faces_granted);
      REQUIRE(y.faces_used == x.faces_used);
      REQUIRE(y.live_probes == x.live_probes);
      REQUIRE(y.bytes == x.bytes);
      REQUIRE(y.demand_points == x.demand_points);
      REQUIRE((y.coverage == x.coverage || (std::isnan(y.coverage) && std::isnan(x.coverage))));
    }
    CHECK(without.camera_path == with.camera_path);
    // What the planner held, node by node, at every snapshot.
    REQUIRE(without.snapshots.size() == with.snapshots.size());
    for (std::size_t s = 0; s < with.snapshots.size(); ++s) {
      const auto& x = with.snapshots[s].nodes;
      const auto& y = without.snapshots[s].nodes;
      REQUIRE(y.size() == x.size());
      for (std::size_t n = 0; n < x.size(); ++n) {
        REQUIRE(y[n].centre == x[n].centre);
        REQUIRE(y[n].has_data == x[n].has_data);
        REQUIRE(y[n].in_flight == x[n].in_flight);
        REQUIRE(y[n].sh == x[n].sh);
      }
    }

    // What needs the reference: not scored.
    CHECK(b.samples == 0);
    CHECK(b.receiver_frames == 0);
    CHECK(b.pops.count == 0);
    CHECK(without.exposure == 0.0);
    CHECK(a.samples > 0);
  }
}

TEST_CASE("the oracle cannot run without a reference", "[simulation]") {
  auto& f = small_drive();
  auto oracle = make_planner("oracle");
  CHECK_THROWS_AS(simulate_without_reference(f.scenario, f.world, *oracle), std::invalid_argument);
}
