// ambisim under lighting that changes: refresh by expected error (drift), the rescale by the
// scene's light level, and the lamp layer (tests/support/planner_harness.h drives it).
#include <catch2/catch.hpp>
#include <cmath>
#include <functional>
#include <map>
#include <vector>

#include <glm/geometric.hpp>

#include "policies/ambisim/demand_planner.h"
#include "policies/registry/registry.h"
#include "tests/support/planner_harness.h"

using namespace ambisim;
using test::constant_sh;
using test::Harness;
using test::kFrame;
using test::TestWorld;

namespace {

// The far field's cells sum in float before dividing by their weight (the linear scan sums
// directly): its coefficients agree with the scan's to this, absolutely (values are ~1).
constexpr float kRefreshFarFieldTolerance = 1e-5f;

PlannerParams params(std::vector<std::string> extra) {
  // The lifetime far away: only refreshes recapture in these tests.
  extra.push_back("lifetime_s=1000");
  extra.push_back("precision=fp32");
  return planner_params_from_cli("ambisim", extra);
}

}  // namespace

TEST_CASE("ambisim refreshes a probe each time its drift reaches refresh_drift", "[ambisim]") {
  // The light changes at 0.01 per second within 10 m of the origin and nowhere else: probes
  // there are captured again every refresh_drift / rate = 0.04 / 0.01 = 4 s (to a frame), the
  // others never.
  auto p = make_planner("ambisim", params({"learn_sensitivity=false", "rescale=false"}));
  TestWorld w;
  w.rate = [](const glm::dvec3& q, double) { return std::hypot(q.x, q.y) < 10.0 ? 0.01 : 0.0; };
  Harness h{*p, w};
  h.run_until(60.0);
  // The probe at the camera's predicted position (the first capture).
  REQUIRE(!h.started.empty());
  const glm::dvec3 first = h.started.front().second.position;
  const auto times = h.starts_at(first, 0.0, 60.0);
  REQUIRE(times.size() >= 10);
  for (std::size_t k = 2; k < times.size(); ++k) {
    INFO("refresh " << k << " at " << times[k]);
    CHECK(times[k] - times[k - 1] == Approx(4.0).margin(2.0 * kFrame));
  }
  // Probes beyond 10 m: captured once.
  std::map<std::pair<long, long>, int> far;
  for (const auto& [t, r] : h.started) {
    if (std::hypot(r.position.x, r.position.y) > 11.0) {
      ++far[{std::lround(r.position.x * 100), std::lround(r.position.y * 100)}];
    }
  }
  REQUIRE(!far.empty());
  for (const auto& [key, n] : far) CHECK(n == 1);
}

TEST_CASE("ambisim does nothing new when the light does not change", "[ambisim]") {
  // A static world (lighting_static): refresh=error and refresh=lifetime give the same captures
  // and the same lookups, bit for bit.
  auto run = [](const std::string& refresh) {
    auto p = make_planner("ambisim", params({"refresh=" + refresh}));
    TestWorld w;
    w.queries.lighting_static = true;
    w.rate = [](const glm::dvec3&, double) { return 0.5; };  // ignored: the world is static
    Harness h{*p, w};
    h.run_until(20.0);
    std::vector<float> seen;
    for (double x = -40.0; x <= 40.0; x += 7.0) seen.push_back(p->lookup({x, 3.0, 1.2}).sh.c[0].x);
    return std::make_pair(h.started.size(), seen);
  };
  const auto a = run("error"), b = run("lifetime");
  CHECK(a.first == b.first);
  CHECK(a.second == b.second);
}

TEST_CASE("ambisim rescales its probes by the scene's light level between refreshes", "[ambisim]") {
  // The sky brightens by (2, 3, 0.5) per channel at 30 s; no rate is reported, so no probe is
  // captured again: lookups show the captured value times the level now over the level then.
  auto p = make_planner("ambisim", params({}));
  TestWorld w;
  w.base_light = [](const glm::dvec3& q, double) {
    return Rgb(0.3f + 0.001f * static_cast<float>(q.x), 0.5f, 0.7f);
  };
  Harness h{*p, w};
  h.run_until(29.0);
  const glm::dvec3 at = h.started.front().second.position;
  const Rgb before = p->lookup(at).sh.c[0];
  w.info.sky_sh = constant_sh(Rgb(2.0f, 3.0f, 0.5f));
  const std::size_t captures = h.started.size();
  h.run_until(31.0);
  const Rgb after = p->lookup(at).sh.c[0];
  CHECK(h.started.size() == captures);
  CHECK(after.x == Approx(2.0f * before.x).epsilon(1e-6));
  CHECK(after.y == Approx(3.0f * before.y).epsilon(1e-6));
  CHECK(after.z == Approx(0.5f * before.z).epsilon(1e-6));
  auto off = make_planner("ambisim", params({"rescale=false"}));
  TestWorld w2;
  Harness h2{*off, w2};
  h2.run_until(29.0);
  const Rgb b2 = off->lookup(at).sh.c[0];
  w2.info.sky_sh = constant_sh(Rgb(2.0f, 3.0f, 0.5f));
  h2.run_until(31.0);
  CHECK(off->lookup(at).sh.c[0] == b2);
}

TEST_CASE("ambisim's lamp layer: a switch costs no recapture, without it, near ones refresh",
          "[ambisim]") {
  // One lamp at (0, 0, 10) reaching 15 m; it switches on at 20 s (the world reports 1/s for
  // 0.5 s either side). Captures within reach (plus a spacing) render a lamp layer; lookups
  // there add the lamps' light times their level.
  const glm::dvec3 lamp{0.0, 0.0, 10.0};
  const auto make_world = [&](TestWorld& w) {
    w.queries.has_lamps = true;
    w.queries.lamp_positions = {lamp};
    w.queries.lamp_reach_m = 15.0;
    w.lamp_light = [&](const glm::dvec3& q) {
      const double d = std::hypot(q.x - lamp.x, q.y - lamp.y);
      return d < 18.0 ? Rgb(0.8f, 0.6f, 0.2f) : Rgb(0.0f);
    };
    w.lamp_level = [](double t) { return t >= 20.0 ? 1.0 : 0.0; };
    w.lamp_rate = [](double t) { return std::abs(t - 20.0) <= 0.5 ? 1.0 : 0.0; };
  };
  SECTION("with the layer") {
    auto p = make_planner("ambisim", params({}));
    TestWorld w;
    make_world(w);
    Harness h{*p, w};
    h.run_until(19.0);
    const CaptureRequest first = h.started.front().second;
    CHECK(first.lamp_layer);  // at the camera, under the lamp
    bool far_without = false;
    for (const auto& [t, r] : h.started) {
      const double d = std::hypot(r.position.x, r.position.y);
      if (d > 18.0 + 3.0) far_without = far_without || !r.lamp_layer;
      if (d > 18.0 + 3.0) CHECK_FALSE(r.lamp_layer);
    }
    CHECK(far_without);
    const Rgb off = p->lookup(first.position).sh.c[0];
    CHECK(off.x == Approx(1.0f));
    const std::size_t before = h.started.size();
    h.run_until(40.0);
    CHECK(h.started.size() == before);  // the switch: no capture
    const Rgb on = p->lookup(first.position).sh.c[0];
    CHECK(on.x == Approx(1.8f));
    CHECK(on.y == Approx(1.6f));
    CHECK(on.z == Approx(1.2f));
  }
  SECTION("without it") {
    auto p = make_planner("ambisim", params({"lamp_layer=false"}));
    TestWorld w;
    make_world(w);
    Harness h{*p, w};
    h.run_until(19.0);
    for (const auto& [t, r] : h.started) CHECK_FALSE(r.lamp_layer);
    const std::size_t before = h.started.size();
    h.run_until(40.0);
    // Every probe within reach is captured again, none beyond it.
    std::size_t near = 0;
    for (const auto& [t, r] : h.started) {
      if (t < 19.0 || std::hypot(r.position.x, r.position.y) > 15.0 + 3.0) continue;
      ++near;
    }
    CHECK(near > 0);
    CHECK(h.started.size() - before == near);
    CHECK(p->lookup(h.started.front().second.position).sh.c[0].x == Approx(1.8f));
  }
}

TEST_CASE("ambisim learns how much of the world's rate a probe's light follows", "[ambisim]") {
  // The world reports 0.01 per second everywhere but the captured light changes at a quarter
  // of it (a probe in shadow does not follow the sun's dimming): with learning the refreshes
  // space out toward 4 x 4 s; without, every 4 s.
  const auto interval = [](bool learn) {
    auto p = make_planner(
        "ambisim",
        params({std::string("learn_sensitivity=") + (learn ? "true" : "false"), "rescale=false"}));
    TestWorld w;
    w.rate = [](const glm::dvec3&, double) { return 0.01; };
    w.base_light = [](const glm::dvec3&, double t) {
      return Rgb(static_cast<float>(std::exp(0.0025 * t)));
    };
    Harness h{*p, w};
    h.run_until(200.0);
    const auto times = h.starts_at(h.started.front().second.position, 0.0, 200.0);
    REQUIRE(times.size() >= 4);
    return times[times.size() - 1] - times[times.size() - 2];
  };
  CHECK(interval(false) == Approx(4.0).margin(2.0 * kFrame));
  // The sensitivity converges to the observed 0.25 (halfway each refresh): 16 s.
  CHECK(interval(true) == Approx(16.0).margin(1.0));
}

TEST_CASE("ambisim's far field follows refreshed probes: lookups equal the linear scan",
          "[ambisim]") {
  // Without the rescale the light level never moves the far field's sums: only fades and
  // refreshes do, and follow_probes() redoes just the probes that are not steady. The light
  // near the origin keeps changing, so each refresh (every 4 s) brings a new value that fades
  // in; a refreshed probe left out of the next refill would leave the far field's sums on its
  // old value, and lookups that read the far field off the linear scan's.
  auto p = make_planner("ambisim", params({"learn_sensitivity=false", "rescale=false"}));
  auto* ambisim = dynamic_cast<DemandPlanner*>(p.get());
  REQUIRE(ambisim != nullptr);
  TestWorld w;
  w.rate = [](const glm::dvec3& q, double) { return std::hypot(q.x, q.y) < 10.0 ? 0.01 : 0.0; };
  w.base_light = [](const glm::dvec3& q, double t) {
    const float near = std::hypot(q.x, q.y) < 10.0 ? static_cast<float>(0.02 * t) : 0.0f;
    return Rgb(0.5f + near, 0.6f, 0.4f + 0.5f * near);
  };
  Harness h{*p, w};
  std::size_t far_read = 0;
  for (int round = 0; round < 40; ++round) {
    h.run_until(h.time() + 0.75);
    for (double x = -60.0; x <= 60.0; x += 6.5) {
      for (double y = -30.0; y <= 30.0; y += 7.5) {
        const glm::dvec3 q{x, y, 1.2};
        if (!ambisim->lookup_uses_far_field(q)) continue;
        ++far_read;
        const LookupResult fast = p->lookup(q), slow = ambisim->lookup_reference(q);
        INFO("t " << h.time() << " at " << x << " " << y);
        for (int i = 0; i < kShCount; ++i) {
          for (int ch = 0; ch < 3; ++ch) {
            REQUIRE(std::abs(fast.sh.c[i][ch] - slow.sh.c[i][ch]) <= kRefreshFarFieldTolerance);
          }
        }
      }
    }
  }
  CHECK(far_read > 100);
}
