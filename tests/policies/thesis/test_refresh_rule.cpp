// The thesis' refresh rule (7.5.3) in SHGraph and the octree: sets are renewed when the light
// may have changed by refresh_tolerance, at the rate the world reports.
#include <catch2/catch.hpp>

#include "policies/registry/registry.h"
#include "tests/support/planner_harness.h"

using namespace ambisim;

namespace {

// A renewal is never earlier than the rule says, and later only by the wait for the budget
// (two captures in flight at a time, 6 frames each, shared by every anchor due).
void check_gaps(const std::vector<double>& gaps, double rule_s) {
  for (std::size_t k = 1; k < gaps.size(); ++k) {  // the first follows the initial fill
    INFO("gap " << k);
    CHECK(gaps[k] >= rule_s - 1.5 * test::kFrame);
    CHECK(gaps[k] <= rule_s + 0.15);
  }
}

// Times between the captures at the first capture's position over `seconds` of a hovering
// camera.
std::vector<double> renewal_intervals(const std::string& planner, std::vector<std::string> set,
                                      double rate, double seconds = 40.0) {
  auto p = make_planner(planner, planner_params_from_cli(planner, set));
  test::TestWorld w;
  w.info.sun_sky_change_rate = rate;
  w.rate = [rate](const glm::dvec3&, double) { return rate; };
  test::Harness h(*p, w);
  h.run_until(seconds);
  REQUIRE(!h.started.empty());
  const auto times = h.starts_at(h.started.front().second.position, 0.0, seconds);
  std::vector<double> out;
  for (std::size_t k = 1; k < times.size(); ++k) out.push_back(times[k] - times[k - 1]);
  return out;
}

}  // namespace

TEST_CASE("SHGraph renews a set at refresh_tolerance / rate less its margin", "[refresh_rule]") {
  // The thesis' margin: 2 capture latencies + 1 s = 1.2 s at 1 face per frame, real time.
  // The sheet at 0.01 per second with tolerance 0.04: a set lasts 4 s, renewed after 2.8 s.
  const auto sheet = renewal_intervals("shgraph2d", {}, 0.01);
  REQUIRE(sheet.size() >= 8);
  check_gaps(sheet, 4.0 - 1.2);
  // The 3D graph holds ~5x more anchors than the budget renews every 4 s: at 0.002 per second
  // a set lasts 20 s, renewed after 18.8 s.
  for (const std::string planner : {"shgraph", "shgraph+vp"}) {
    INFO(planner);
    const auto gaps = renewal_intervals(planner, {}, 0.002, 80.0);
    REQUIRE(gaps.size() >= 3);
    check_gaps(gaps, 20.0 - 1.2);
  }
  for (const std::string planner : {"shgraph", "shgraph2d"}) {
    INFO(planner);
    // refresh=lifetime: renewed only at lifetime_s - margin (58.8 s): never in 40 s.
    CHECK(renewal_intervals(planner, {"refresh=lifetime"}, 0.01).empty());
    // Light that changes slowly: real time bounds the clock from below (lifetime_s).
    CHECK(renewal_intervals(planner, {}, 0.0001).empty());
  }
}

TEST_CASE("the octree renews its sets by the rule when asked, in either retention",
          "[refresh_rule]") {
  for (const std::string retention : {"cap", "lifetime"}) {
    INFO(retention);
    const auto gaps = renewal_intervals("octree", {"refresh=rate", "retention=" + retention}, 0.01);
    REQUIRE(gaps.size() >= 8);
    // Renewal at clock age lifetime - (renew_margin_s + 2 latencies): 4 s - 1.2 s real.
    check_gaps(gaps, 4.0 - 1.2);
    // The default is the lifetime alone.
    CHECK(renewal_intervals("octree", {"retention=" + retention}, 0.01).empty());
  }
}
