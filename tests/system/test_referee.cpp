// The referee on fast-changing truth (the referee issue): a display that never changes never
// pops, and the oracle's pops do not come from the reference's time interpolation (its
// refinement resolves every abrupt change the every-frame reference sees).
#include <catch2/catch.hpp>

#include "policies/registry/registry.h"
#include "sim/run/reference_track.h"
#include "sim/run/simulator.h"
#include "sim/scenario/scenario.h"
#include "sim/world/world.h"
#include "tests/support/scenario_fixtures.h"

using namespace ambisim;

namespace {

// A shipped fast-changing scenario cut to `seconds`, with its reference on the 0.1 s grid and
// refined (as shipped) or captured every frame.
Scenario cut(const std::string& name, double seconds, double interval_s) {
  Scenario s = load_scenario(std::string(AMBISIM_SOURCE_DIR) + "/scenarios/" + name + ".json");
  nlohmann::json d = s.document;
  d["frames"]["duration_s"] = seconds;
  d["reference"]["interval_s"] = interval_s;
  d["reference"]["face_size"] = 12;
  return parse_scenario(d, s.file);
}

Summary run(const Scenario& s, const World& w, const std::string& planner) {
  const auto ref = compute_reference_track(s, w);
  auto p = make_planner(planner);
  return simulate(s, w, *ref, *p).summary;
}

}  // namespace

TEST_CASE("on fast-changing truth the oracle pops no more with the interpolated reference",
          "[referee]") {
  for (const char* name : {"cliff_skim", "rock_circle"}) {
    const Scenario refined = cut(name, 10.0, 0.1);
    const Scenario every = cut(name, 10.0, 0.0);
    const World& w = test::world_for(refined);
    const Summary a = run(refined, w, "oracle");
    const Summary b = run(every, w, "oracle");
    INFO(name);
    CHECK(a.pops.count == b.pops.count);
    CHECK(a.pops_viewed.count == b.pops_viewed.count);
    CHECK(a.de2000.p95 == Approx(b.de2000.p95).margin(0.1));
  }
}

TEST_CASE("a display that never changes never pops, however fast the truth changes", "[referee]") {
  for (const char* name : {"cliff_skim", "rock_circle", "hover_dash"}) {
    const Scenario s = cut(name, 6.0, 0.1);
    const World& w = test::world_for(s);
    const Summary c = run(s, w, "constant");
    INFO(name);
    CHECK(c.pops.count == 0);
    CHECK(c.pops_viewed.count == 0);
    CHECK(c.bake.captures == 1);  // its one capture is taken at load time
    CHECK(c.bake.faces == 6);
    CHECK(c.faces.granted == 0);
  }
}
