// ambisim's own planner: captures where objects are, spaced by distance, and never steps.
#include <catch2/catch.hpp>
#include <cmath>

#include <glm/geometric.hpp>

#include "policies/demand_planner.h"
#include "policies/registry.h"

using namespace ambisim;

namespace {

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

TEST_CASE("ambisim spaces probes like the coverage rule, finer near the camera", "[ambisim]") {
  DemandPlanner p(planner_params_from_cli("ambisim", {}));
  CHECK(p.required_spacing(0.0) == 3.0);
  CHECK(p.required_spacing(10.0) == 3.0);
  CHECK(p.required_spacing(100.0) == Approx(20.0));
}

TEST_CASE("ambisim captures at the objects first, where they will be", "[ambisim]") {
  auto p = make_planner("ambisim");
  p->set_receivers(
      {{7, {50.0, 0.0, 1.0}, {0.0, 10.0, 0.0}}, {3, {5.0, 0.0, 1.0}, {0.0, 0.0, 0.0}}});
  const auto req = p->plan(frame(0.0, {0, 0, 1}, {0, 0, 0}, 1));
  REQUIRE(req.size() == 1);
  // The nearer object (at 5 m) comes first; it does not move, so no prediction.
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
