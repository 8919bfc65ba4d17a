// ambisim's own planner: captures where objects are, spaced by distance, and never steps.
#include <catch2/catch.hpp>
#include <cmath>

#include <glm/geometric.hpp>

#include "policies/ambisim/demand_planner.h"
#include "policies/registry/registry.h"

using namespace ambisim;

namespace {

// Probe A (value 1) at the origin, fully faded in; then the camera moves 6 m so that the
// planner asks for probe B, which arrives with `value`. Returns how long lookups at B's position
// keep changing after B becomes usable (the fade-in it got), in seconds at 60 fps.
double settle_time(Planner& p, float value);

Sh9Rgb constant_sh(float v) {
  Sh9Rgb sh;
  sh.c[0] = Rgb(v);
  return sh;
}

FrameContext frame(double t, glm::dvec3 camera, glm::dvec3 velocity, int startable) {
  FrameContext ctx;
  ctx.time = t;
  ctx.dt = 1.0 / 60.0;
  ctx.frame = static_cast<std::int64_t>(std::llround(t * 60.0));
  ctx.camera_position = camera;
  ctx.camera_velocity = velocity;
  ctx.faces_per_frame = 1.0;
  ctx.startable_captures = startable;
  return ctx;
}

}  // namespace

TEST_CASE("ambisim spaces probes almost evenly, a little coarser far away", "[ambisim]") {
  // Every object counts the same in the error and the pops, wherever it is: the spacing grows
  // only slowly with distance (0.03 per metre beyond 3 m spacing, i.e. from 100 m on).
  DemandPlanner p(planner_params_from_cli("ambisim", {}));
  CHECK(p.required_spacing(0.0) == 3.0);
  CHECK(p.required_spacing(100.0) == Approx(3.0));
  CHECK(p.required_spacing(150.0) == Approx(4.5));
  DemandPlanner q(planner_params_from_cli("ambisim", {"spacing_per_m=0.2"}));
  CHECK(q.required_spacing(100.0) == Approx(20.0));
}

TEST_CASE("ambisim spaces near probes wider when the budget is below 1 face per frame",
          "[ambisim]") {
  // As many probes per area as the budget sustains: spacing x sqrt(1 / faces per frame), but
  // never coarser than 4 m (the coverage rule's near spacing).
  DemandPlanner p(planner_params_from_cli("ambisim", {}));
  p.set_budget(0.8);
  CHECK(p.required_spacing(0.0) == Approx(3.0 * std::sqrt(1.25)));
  CHECK(p.required_spacing(200.0) == Approx(6.0));  // the far rule is unchanged
  p.set_budget(0.5);
  CHECK(p.required_spacing(0.0) == Approx(4.0));
  p.set_budget(0.25);
  CHECK(p.required_spacing(0.0) == Approx(4.0));
  DemandPlanner fine(planner_params_from_cli("ambisim", {"min_spacing_m=1"}));
  fine.set_budget(0.25);
  CHECK(fine.required_spacing(0.0) == Approx(2.0));
  p.set_budget(2.0);  // never finer than min_spacing_m
  CHECK(p.required_spacing(0.0) == Approx(3.0));
  p.set_budget(0.0);  // no budget: nothing to spread
  CHECK(p.required_spacing(0.0) == Approx(3.0));
  DemandPlanner off(planner_params_from_cli("ambisim", {"budget_spacing=false"}));
  off.set_budget(0.5);
  CHECK(off.required_spacing(0.0) == Approx(3.0));
  // plan() takes the frame's budget.
  DemandPlanner r(planner_params_from_cli("ambisim", {}));
  FrameContext ctx = frame(0.0, {0, 0, 1}, {0, 0, 0}, 1);
  ctx.faces_per_frame = 0.5;
  r.plan(ctx);
  CHECK(r.required_spacing(0.0) == Approx(4.0));
}

TEST_CASE("ambisim captures at the objects first, where they will be", "[ambisim]") {
  auto p = make_planner("ambisim");
  p->set_receivers(
      {{7, {50.0, 0.0, 1.0}, {0.0, 10.0, 0.0}}, {3, {5.0, 0.0, 1.0}, {0.0, 0.0, 0.0}}});
  const auto req = p->plan(frame(0.0, {0, 0, 1}, {0, 0, 0}, 1));
  REQUIRE(req.size() == 1);
  // Neither has a probe (equal need): the nearer object (at 5 m) comes first; it does not
  // move, so no prediction.
  CHECK(glm::distance(req[0].position, glm::dvec3(5.0, 0.0, 1.0)) < 1e-9);
  // Never more requests than the simulator can start.
  CHECK(p->plan(frame(0.0, {0, 0, 1}, {0, 0, 0}, 0)).empty());
  // Moving objects are captured where they will be after latency + look-ahead (0.1 + 0.3 s).
  auto q = make_planner("ambisim");
  q->set_receivers({{7, {50.0, 0.0, 1.0}, {0.0, 10.0, 0.0}}});
  const auto r2 = q->plan(frame(0.0, {0, 0, 1}, {0, 0, 0}, 1));
  REQUIRE(r2.size() == 1);
  CHECK(r2[0].position.y == Approx(10.0 * (0.1 + 0.3)));
}

TEST_CASE("ambisim serves the worst-served object first, not the nearest", "[ambisim]") {
  // need = distance to the nearest probe / required spacing (3 m here). The player's vehicle
  // 9.6 m from the camera has a probe 1.6 m away (need 0.53, still short of a probe: > half a
  // spacing); a prop 40 m away has none closer than 32 m (need 10.7): the prop goes first.
  auto p = make_planner("ambisim");
  p->set_receivers({{0, {8.0, 0.0, 1.0}, {0.0, 0.0, 0.0}}});
  const auto a = p->plan(frame(0.0, {0, 0, 1}, {0, 0, 0}, 1));
  REQUIRE(a.size() == 1);
  CHECK(glm::distance(a[0].position, glm::dvec3(8.0, 0.0, 1.0)) < 1e-9);
  p->started(a[0].tag);
  p->deliver({a[0].tag, a[0].position, constant_sh(1.0f), 0.0, 0.1});
  p->update(frame(0.1, {0, 0, 1}, {0, 0, 0}, 0));
  p->set_receivers({{0, {9.6, 0.0, 1.0}, {0.0, 0.0, 0.0}}, {5, {40.0, 0.0, 1.0}, {0, 0, 0}}});
  const auto one = p->plan(frame(0.2, {0, 0, 1}, {0, 0, 0}, 1));
  REQUIRE(one.size() == 1);
  CHECK(glm::distance(one[0].position, glm::dvec3(40.0, 0.0, 1.0)) < 1e-9);
  // With room for two, the vehicle follows.
  const auto two = p->plan(frame(0.2, {0, 0, 1}, {0, 0, 0}, 2));
  REQUIRE(two.size() == 2);
  CHECK(glm::distance(two[0].position, glm::dvec3(40.0, 0.0, 1.0)) < 1e-9);
  CHECK(glm::distance(two[1].position, glm::dvec3(9.6, 0.0, 1.0)) < 1e-9);
  // priority=distance keeps the old order: nearest first.
  auto d = make_planner("ambisim", planner_params_from_cli("ambisim", {"priority=distance"}));
  d->set_receivers({{0, {9.6, 0.0, 1.0}, {0.0, 0.0, 0.0}}, {5, {40.0, 0.0, 1.0}, {0, 0, 0}}});
  const auto near = d->plan(frame(0.0, {0, 0, 1}, {0, 0, 0}, 1));
  REQUIRE(near.size() == 1);
  CHECK(glm::distance(near[0].position, glm::dvec3(9.6, 0.0, 1.0)) < 1e-9);
}

TEST_CASE("ambisim lookups never step when a probe arrives, and fade in over fade_s", "[ambisim]") {
  auto p = make_planner("ambisim");
  // Before any data: a fallback, finite.
  const LookupResult cold = p->lookup({0, 0, 1});
  CHECK(cold.fell_back);
  double t = 0.0;
  auto step = [&](int startable) {
    auto req = p->plan(frame(t, {0, 0, 1}, {0, 0, 0}, startable));
    for (const auto& r : req) p->started(r.tag);
    p->update(frame(t, {0, 0, 1}, {0, 0, 0}, startable));
    return req;
  };
  // First probe A (value 1) at the camera.
  auto a = step(1);
  REQUIRE(a.size() == 1);
  p->deliver({a[0].tag, a[0].position, constant_sh(1.0f), t, t});
  t += 1.0 / 60.0;
  step(0);
  t += 1.0;  // fully faded in
  step(0);
  const glm::dvec3 x{2.5, 0.0, 1.0};  // a receiver between A and the next probe
  CHECK(p->lookup(x).sh.c[0].x == Approx(1.0f));
  // Move the camera so that the planner asks for probe B 5 m away, deliver it with value 3:
  // at the moment it arrives lookups near it do not change, then they move smoothly.
  std::vector<CaptureRequest> b;
  for (int k = 0; k < 600 && b.empty(); ++k) {
    t += 1.0 / 60.0;
    auto req = p->plan(frame(t, {6.0, 0.0, 1.0}, {0, 0, 0}, 1));
    for (const auto& r : req) p->started(r.tag);
    p->update(frame(t, {6.0, 0.0, 1.0}, {0, 0, 0}, 1));
    b = req;
  }
  REQUIRE(b.size() == 1);
  const glm::dvec3 y = 0.5 * (b[0].position + a[0].position);
  const double before = p->lookup(y).sh.c[0].x;
  p->deliver({b[0].tag, b[0].position, constant_sh(3.0f), t, t});
  CHECK(p->lookup(y).sh.c[0].x == Approx(before));  // no step at delivery
  double previous = before;
  double largest_step = 0.0;
  for (int k = 0; k < 60; ++k) {  // 1 s at 60 fps: fade_s = 0.4 s
    t += 1.0 / 60.0;
    p->update(frame(t, {6.0, 0.0, 1.0}, {0, 0, 0}, 0));
    const double v = p->lookup(y).sh.c[0].x;
    largest_step = std::max(largest_step, std::abs(v - previous));
    previous = v;
  }
  CHECK(previous > before + 0.5);                    // it did move toward B's value
  CHECK(largest_step < 0.15 * (previous - before));  // ... in many small steps
}

namespace {

double settle_time(Planner& p, float value) {
  double t = 0.0;
  auto step = [&](glm::dvec3 camera, int startable) {
    auto req = p.plan(frame(t, camera, {0, 0, 0}, startable));
    for (const auto& r : req) p.started(r.tag);
    p.update(frame(t, camera, {0, 0, 0}, startable));
    return req;
  };
  auto a = step({0, 0, 1}, 1);
  REQUIRE(a.size() == 1);
  p.deliver({a[0].tag, a[0].position, constant_sh(1.0f), t, t});
  t += 3.0;
  step({0, 0, 1}, 0);
  std::vector<CaptureRequest> b;
  for (int k = 0; k < 600 && b.empty(); ++k) {
    t += 1.0 / 60.0;
    b = step({6.0, 0.0, 1.0}, 1);
  }
  REQUIRE(b.size() == 1);
  p.deliver({b[0].tag, b[0].position, constant_sh(value), t, t});
  double previous = p.lookup(b[0].position).sh.c[0].x;
  double last_change = 0.0;
  const double start = t + 1.0 / 60.0;  // B is usable from the next frame
  for (int k = 0; k < 240; ++k) {
    t += 1.0 / 60.0;
    step({6.0, 0.0, 1.0}, 0);
    const double v = p.lookup(b[0].position).sh.c[0].x;
    if (std::abs(v - previous) > 1e-6 * std::abs(v)) last_change = t;
    previous = v;
  }
  return last_change - start;
}

}  // namespace

TEST_CASE("ambisim fades a new probe in the slower the more it changes", "[ambisim]") {
  // fade = clamp(|ln(new / old)| / fade_rate, fade_s, fade_max_s) with fade_rate 2 per second,
  // fade_s 0.4 s, fade_max_s 2 s; lookups at the new probe change during exactly that time.
  const double frame_s = 1.0 / 60.0;
  auto planner = [] { return make_planner("ambisim"); };
  // A small change (x1.2: ln 1.2 / 2 = 0.09 s) still takes fade_s.
  CHECK(settle_time(*planner(), 1.2f) == Approx(0.4).margin(1.5 * frame_s));
  // x e^1.6: 0.8 s.
  CHECK(settle_time(*planner(), static_cast<float>(std::exp(1.6))) ==
        Approx(0.8).margin(1.5 * frame_s));
  // Darker by the same factor: the same time.
  CHECK(settle_time(*planner(), static_cast<float>(std::exp(-1.6))) ==
        Approx(0.8).margin(1.5 * frame_s));
  // x e^6 would need 3 s: capped at fade_max_s.
  CHECK(settle_time(*planner(), static_cast<float>(std::exp(6.0))) ==
        Approx(2.0).margin(1.5 * frame_s));
  // fade_rate = 0: always fade_s.
  auto fixed = make_planner("ambisim", planner_params_from_cli("ambisim", {"fade_rate=0"}));
  CHECK(settle_time(*fixed, static_cast<float>(std::exp(1.6))) ==
        Approx(0.4).margin(1.5 * frame_s));
}

TEST_CASE("ambisim's per-receiver memos plan what searching every receiver anew plans",
          "[ambisim]") {
  // Two planners fed the same frames; one forgets its memos before every plan(). Probes come
  // (up to 6 captures per frame) and go (a 64-probe cap, a 2 s lifetime) so that the index is
  // rebuilt often both ways: on deliveries and on dropping the probes that left. Receivers:
  // some stand still for good, some are replaced by new ones every 40 frames and some move with
  // the camera (a new point every frame).
  const PlannerParams params =
      planner_params_from_cli("ambisim", {"max_probes=64", "lifetime_s=2", "max_distance_m=60"});
  DemandPlanner memo(params), fresh(params);
  struct Flight {
    CaptureRequest request;
    double start;
    std::int64_t due;
  };
  std::vector<Flight> flight;
  std::size_t delivered = 0, requests = 0;
  std::uint64_t next_id = 1000;
  std::vector<Planner::ReceiverView> receivers;
  for (std::int64_t f = 0; f < 1500; ++f) {
    const double t = static_cast<double>(f) / 60.0;
    const double a = 0.3 * t;  // the camera circles the origin at 24 m/s
    const glm::dvec3 camera{80.0 * std::cos(a), 80.0 * std::sin(a), 2.0};
    const glm::dvec3 velocity{-24.0 * std::sin(a), 24.0 * std::cos(a), 0.0};
    if (f % 40 == 0) {
      receivers.clear();
      for (int i = 0; i < 20; ++i) {  // standing for good, ids 1..20
        const double b = 0.3 * i;
        receivers.push_back({static_cast<std::uint64_t>(i + 1),
                             {80.0 * std::cos(b) + 3.0, 80.0 * std::sin(b) - 2.0, 1.0},
                             glm::dvec3(0.0)});
      }
      for (int i = 0; i < 40; ++i) {  // replaced every 40 frames
        receivers.push_back({next_id++,
                             camera + glm::dvec3(1.7 * (i % 8) - 6.0, 2.3 * (i / 8) - 5.0, -1.0),
                             glm::dvec3(0.0)});
      }
    }
    receivers.resize(60);
    for (int i = 0; i < 10; ++i) {  // with the camera, ids 100..109
      receivers.push_back({static_cast<std::uint64_t>(100 + i),
                           camera + glm::dvec3(0.8 * i, -1.5, -1.0), velocity});
    }
    FrameContext ctx = frame(t, camera, velocity, 6);
    ctx.frame = f;
    ctx.camera_cut = f == 0;
    const int owed = static_cast<int>(flight.size());
    ctx.startable_captures = std::max(0, 6 - owed);
    memo.set_receivers(receivers);
    fresh.set_receivers(receivers);
    fresh.forget_nearest_memos();
    const auto got = memo.plan(ctx);
    const auto want = fresh.plan(ctx);
    REQUIRE(got.size() == want.size());
    for (std::size_t k = 0; k < got.size(); ++k) {
      INFO("frame " << f << ", request " << k);
      REQUIRE(got[k].position == want[k].position);
      REQUIRE(got[k].tag == want[k].tag);
    }
    requests += got.size();
    for (std::size_t k = 0; k < got.size(); ++k) {
      if (static_cast<int>(k) < ctx.startable_captures) {
        memo.started(got[k].tag);
        fresh.started(got[k].tag);
        flight.push_back({got[k], t, f + 3});
      } else {
        memo.refused(got[k].tag);
        fresh.refused(got[k].tag);
      }
    }
    memo.update(ctx);
    fresh.update(ctx);
    while (!flight.empty() && flight.front().due <= f) {
      const Flight& c = flight.front();
      const FinishedProbe probe{c.request.tag, c.request.position,
                                constant_sh(static_cast<float>(1.0 + 0.01 * (delivered % 7))),
                                c.start, t};
      memo.deliver(probe);
      fresh.deliver(probe);
      flight.erase(flight.begin());
      ++delivered;
    }
  }
  // Far more probes came than the cap holds: many rebuilds dropped probes that had left.
  CHECK(delivered > 20 * 64);
  CHECK(requests >= delivered);
  CHECK(memo.stats().live_probes == fresh.stats().live_probes);
}
