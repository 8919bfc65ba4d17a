// A game's load: the referee scores a sample of the receivers (every k-th of each kind) while
// the planner lights all of them. On a run small enough to score in full, the full score lies
// within the sample's 95% interval, the sample is the size it says, and the planner's own
// behaviour does not depend on the sample.
#include <catch2/catch.hpp>

#include "policies/registry/registry.h"
#include "sim/run/reference_track.h"
#include "sim/run/simulator.h"
#include "sim/scenario/scenario.h"
#include "sim/world/world.h"
#include "tests/support/scenario_fixtures.h"

using namespace ambisim;

namespace {

// rush_hour cut to `seconds` with a cheap reference, scoring every `stride`-th receiver.
Scenario rush_hour(double seconds, int stride) {
  Scenario s = load_scenario(std::string(AMBISIM_SOURCE_DIR) + "/scenarios/rush_hour.json");
  nlohmann::json d = s.document;
  d["frames"]["duration_s"] = seconds;
  d["reference"]["face_size"] = 8;
  d["reference"]["sample_stride"] = stride;
  return parse_scenario(d, s.file);
}

RunResult run(const Scenario& s, const std::string& planner) {
  const World& w = test::world_for(s);
  const auto ref = compute_reference_track(s, w);
  auto p = make_planner(planner);
  return simulate(s, w, *ref, *p);
}

}  // namespace

TEST_CASE("the sampled referee's interval holds the full score, and the planner is unaffected",
          "[referee][sample][heavy]") {
  const double seconds = 8.0;
  for (const char* planner : {"ambisim", "nearest"}) {
    INFO(planner);
    const RunResult full = run(rush_hour(seconds, 1), planner);
    const RunResult sampled = run(rush_hour(seconds, 4), planner);
    const Summary& f = full.summary;
    const Summary& s = sampled.summary;
    // Every receiver is still lit through the planner: same lookups, same captures, same probes.
    CHECK(full.timing.lookups == sampled.timing.lookups);
    CHECK(f.faces.granted == s.faces.granted);
    CHECK(f.probes.max_live == s.probes.max_live);
    CHECK(f.memory.max_bytes == s.memory.max_bytes);
    // The sample is a quarter of the receivers, within one per kind of rounding.
    REQUIRE(f.sample.receivers_lit > 200);
    CHECK(f.sample.receivers_scored == f.sample.receivers_lit);
    CHECK(s.sample.receivers_lit == f.sample.receivers_lit);
    CHECK(std::abs(static_cast<double>(s.sample.receivers_scored) -
                   static_cast<double>(f.sample.receivers_lit) / 4.0) <= 2.0);
    CHECK(s.receiver_frames < f.receiver_frames / 3);
    // Full scores are exact (no interval); the sample's 95% intervals hold them.
    CHECK(std::isnan(f.sample.ci95.de2000_mean.low));
    const auto within = [](const Interval& i, double x) {
      INFO("interval [" << i.low << ", " << i.high << "], full " << x);
      CHECK(i.low < i.high);
      CHECK(x >= i.low);
      CHECK(x <= i.high);
    };
    within(s.sample.ci95.de2000_mean, f.de2000.mean);
    within(s.sample.ci95.de2000_viewed_mean, f.de2000_viewed.mean);
    within(s.sample.ci95.pops_per_min, f.pops.per_min);
    // The sample's own point estimates lie within their intervals too.
    within(s.sample.ci95.de2000_mean, s.de2000.mean);
    within(s.sample.ci95.pops_per_min, s.pops.per_min);
  }
}
