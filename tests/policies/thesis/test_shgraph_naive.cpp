// The SHGraph's fast paths (update() visiting only the anchors it can change, the shared
// neighbourhood walk and fused accumulation of lookup()) against its naive reference paths
// (ShGraphCore::set_naive): byte-identical results, views and node sets on every scenario,
// with the default lifetime and with one short enough that sets expire and are renewed.
#include <catch2/catch.hpp>
#include <filesystem>
#include <map>

#include "policies/registry/registry.h"
#include "policies/thesis/shgraph.h"
#include "policies/thesis/shgraph2d.h"
#include "sim/base/json_reader.h"
#include "sim/run/reference_track.h"
#include "sim/run/run_output.h"
#include "sim/scenario/scenario.h"
#include "sim/world/world.h"
#include "tests/support/scenario_fixtures.h"

using namespace ambisim;
using ambisim::test::short_scenarios;
using ambisim::test::world_for;

namespace {

std::unique_ptr<Planner> make(const std::string& name, const std::vector<std::string>& set,
                              bool naive) {
  auto p = make_planner(name, planner_params_from_cli(name, set));
  if (auto* g = dynamic_cast<ShGraphPlanner*>(p.get())) g->set_naive(naive);
  if (auto* g = dynamic_cast<ShGraph2dPlanner*>(p.get())) g->set_naive(naive);
  return p;
}

std::string everything(const Scenario& sc, const Planner& p, const RunResult& r) {
  return result_json(sc, {p.name(), p.params()}, r).dump(1) + frames_csv(r) + views_json(r);
}

}  // namespace

TEST_CASE("SHGraph fast paths give byte-identical results to the naive ones", "[shgraph][heavy]") {
  const auto scenarios = short_scenarios(6.0, /*with_small_drive=*/true);
  for (const auto& sc : scenarios) {
    const World& world = world_for(sc);
    const auto reference = compute_reference_track(sc, world);
    for (const char* name : {"shgraph", "shgraph+vp", "shgraph+route", "shgraph2d"}) {
      // Default lifetime; and 2 s lifetime with a 0.5 s fade, so that sets are renewed,
      // expire while in flight and fade over each other within the run.
      for (const auto& set :
           std::vector<std::vector<std::string>>{{}, {"lifetime_s=2", "fade_s=0.5"}}) {
        INFO(sc.name << " " << name << " " << set.size());
        auto fast = make(name, set, false);
        auto naive = make(name, set, true);
        const RunResult a = simulate(sc, world, *reference, *fast);
        const RunResult b = simulate(sc, world, *reference, *naive);
        CHECK(a.captures_delivered > 0);
        CHECK(everything(sc, *fast, a) == everything(sc, *naive, b));
        // And the structure at the end, lookups at points all around the last camera position.
        CHECK(fast->stats().live_probes == naive->stats().live_probes);
        CHECK(fast->stats().bytes == naive->stats().bytes);
        const glm::dvec3 c = a.camera_path.back();
        for (int i = -12; i <= 12; ++i) {
          for (int j = -12; j <= 12; ++j) {
            const glm::dvec3 p = c + glm::dvec3(7.3 * i, 6.1 * j, 0.37 * (i - j));
            const LookupResult x = fast->lookup(p);
            const LookupResult y = naive->lookup(p);
            REQUIRE(x.sh == y.sh);
            REQUIRE(x.contributor_count == y.contributor_count);
            REQUIRE(x.data_time == y.data_time);
            REQUIRE(x.spacing_m == y.spacing_m);
            REQUIRE(x.fell_back == y.fell_back);
          }
        }
      }
    }
  }
}
