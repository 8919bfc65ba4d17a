// The oracle and the baselines driven by a small fake frame loop (plan -> started/refused ->
// update -> lookup -> deliver, as sim/planner.h documents) with synthetic probes.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <numbers>

#include "policies/core/default_ambient.h"
#include "policies/registry/registry.h"
#include "sim/planner.h"
#include "sim/sh/sh9.h"

using namespace ambisim;

namespace {

// A set whose 27 values are all different and non-zero.
Sh9Rgb distinct_sh(float base) {
  Sh9Rgb s;
  for (int k = 0; k < kShCount; ++k) {
    s.c[k] = Rgb(base + 0.1f * k, base + 0.1f * k + 0.03f, base + 0.1f * k + 0.07f);
  }
  return s;
}

// The projection of a uniform radiance L: only L00 = sqrt(4 pi) L.
Sh9Rgb uniform_sh(Rgb radiance) {
  Sh9Rgb s;
  s.c[0] = radiance * static_cast<float>(4.0 * std::numbers::pi * kShY00);
  return s;
}

FrameContext frame_at(std::int64_t frame, double dt, glm::dvec3 camera, int startable = 1) {
  FrameContext c;
  c.frame = frame;
  c.dt = dt;
  c.time = static_cast<double>(frame) * dt;
  c.camera_position = camera;
  c.startable_captures = startable;
  return c;
}

FinishedProbe probe_of(const CaptureRequest& r, Sh9Rgb sh, double requested, double finished) {
  return {r.tag, r.position, sh, requested, finished};
}

std::unique_ptr<Planner> nearest_with(const std::vector<std::string>& sets) {
  return make_planner("nearest", planner_params_from_cli("nearest", sets));
}

}  // namespace

TEST_CASE("oracle returns exactly the probe delivered at each receiver", "[policies]") {
  auto p = make_planner("oracle");
  REQUIRE(p->ignores_budget());
  // Before any delivery: the default ambient, fell back.
  LookupResult none = p->lookup({0, 0, 0});
  CHECK(none.fell_back);
  CHECK(none.sh == default_ambient_sh());

  const glm::dvec3 a{1.0, 2.0, 3.0}, b{10.0, 2.0, 3.0};
  p->set_receivers({{7, a, {0, 0, 0}}, {8, b, {0, 0, 0}}});
  auto ctx = frame_at(0, 0.1, {0, 0, 0}, /*startable=*/0);  // the oracle ignores the budget
  const auto req = p->plan(ctx);
  REQUIRE(req.size() == 2);
  CHECK(req[0].position == a);
  CHECK(req[1].position == b);
  CHECK(req[0].tag != req[1].tag);
  for (const auto& r : req) p->started(r.tag);
  p->deliver(probe_of(req[0], distinct_sh(1.0f), 0.0, 0.0));  // delivered before the lookups
  p->deliver(probe_of(req[1], distinct_sh(5.0f), 0.0, 0.0));
  p->update(ctx);

  const LookupResult la = p->lookup(a);
  CHECK(la.sh == distinct_sh(1.0f));
  CHECK_FALSE(la.fell_back);
  CHECK(la.spacing_m == 0.0);
  REQUIRE(la.contributor_count == 1);
  CHECK(la.contributors[0].tag == req[0].tag);
  CHECK(la.contributors[0].weight == 1.0f);
  CHECK(p->lookup(b).sh == distinct_sh(5.0f));
  const LookupResult off = p->lookup({8.0, 2.0, 3.0});  // not a receiver: the nearest probe
  CHECK(off.sh == distinct_sh(5.0f));
  CHECK(off.spacing_m == Approx(2.0));
  CHECK(p->stats().live_probes == 2);

  // Next frame: the receivers moved; the new batch replaces the old one.
  const glm::dvec3 a2{1.5, 2.0, 3.0};
  p->set_receivers({{7, a2, {0, 0, 0}}});
  ctx = frame_at(1, 0.1, {0, 0, 0}, 0);
  const auto req2 = p->plan(ctx);
  REQUIRE(req2.size() == 1);
  CHECK(req2[0].tag != req[0].tag);
  p->started(req2[0].tag);
  p->deliver(probe_of(req2[0], distinct_sh(9.0f), 0.1, 0.1));
  p->update(ctx);
  CHECK(p->lookup(a2).sh == distinct_sh(9.0f));
  CHECK(p->lookup(b).sh == distinct_sh(9.0f));  // the old receiver probe is gone
  CHECK(p->lookup(b).spacing_m == Approx(8.5));
  CHECK(p->stats().live_probes == 1);
}

TEST_CASE("constant captures once at the start and keeps only L00", "[policies]") {
  auto p = make_planner("constant", planner_params_from_cli("constant", {"colour_b=1"}));
  const glm::dvec3 cam{3.0, 4.0, 5.0};

  // Nothing startable: no request (and so no refusal to count).
  CHECK(p->plan(frame_at(0, 0.1, cam, 0)).empty());
  // Refused: asked again next frame, under a fresh tag.
  auto r1 = p->plan(frame_at(1, 0.1, cam));
  REQUIRE(r1.size() == 1);
  CHECK(r1[0].position == cam);
  p->refused(r1[0].tag);
  auto r2 = p->plan(frame_at(2, 0.1, cam + glm::dvec3(1, 0, 0)));
  REQUIRE(r2.size() == 1);
  CHECK(r2[0].tag != r1[0].tag);
  CHECK(r2[0].position == cam + glm::dvec3(1, 0, 0));
  p->started(r2[0].tag);
  CHECK(p->plan(frame_at(3, 0.1, cam)).empty());  // one capture only

  // Before delivery: the parameterised colour (0.5, 0.5, 1) as a uniform radiance, fell back.
  const LookupResult before = p->lookup({100, 0, 0});
  CHECK(before.fell_back);
  CHECK(std::isinf(before.spacing_m));
  CHECK(before.contributor_count == 0);
  for (const glm::dvec3 n : {glm::dvec3(0, 0, 1), glm::dvec3(0, 0, -1), glm::dvec3(1, 0, 0)}) {
    const Rgb e = sh_irradiance(before.sh, n);
    CHECK(e.x == Approx(std::numbers::pi * 0.5));
    CHECK(e.z == Approx(std::numbers::pi * 1.0));
  }

  const Sh9Rgb captured = distinct_sh(2.0f);
  p->deliver(probe_of(r2[0], captured, 0.2, 0.8));
  p->update(frame_at(9, 0.1, cam));
  for (const glm::dvec3 q : {glm::dvec3(0, 0, 0), glm::dvec3(-5e3, 7e3, 20)}) {
    const LookupResult r = p->lookup(q);
    CHECK(r.sh.c[0] == captured.c[0]);
    for (int k = 1; k < kShCount; ++k) CHECK(r.sh.c[k] == Rgb(0.0f));
    CHECK(r.fell_back);  // no spatial structure: never counts as covered
    CHECK(std::isinf(r.spacing_m));
    REQUIRE(r.contributor_count == 1);
    CHECK(r.contributors[0].tag == r2[0].tag);
    CHECK(r.data_time == 0.2);
  }
  // A second delivery (not asked for) changes nothing: "forever".
  p->deliver(probe_of({cam, 99}, distinct_sh(7.0f), 1.0, 1.0));
  CHECK(p->lookup(cam).sh.c[0] == captured.c[0]);
  CHECK(p->stats().live_probes == 1);
  CHECK(p->stats().bytes >= static_cast<std::int64_t>(sizeof(Sh9Rgb)));
}

TEST_CASE("constant takes its capture at load time, before the first frame", "[policies]") {
  auto p = make_planner("constant");
  const glm::dvec3 cam{3.0, 4.0, 5.0};
  const auto pre = p->preload(frame_at(0, 1.0 / 60, cam));
  REQUIRE(pre.size() == 1);
  CHECK(pre[0].position == cam);
  // Asked for at load time: plan() does not ask again, delivered or not yet.
  CHECK(p->plan(frame_at(0, 1.0 / 60, cam)).empty());
  p->deliver(probe_of(pre[0], distinct_sh(2.0f), 0.0, 0.0));
  CHECK(p->lookup(cam).sh.c[0] == distinct_sh(2.0f).c[0]);
  CHECK(p->plan(frame_at(1, 1.0 / 60, cam)).empty());
}

TEST_CASE("hemisphere keeps L00 and L10 only, its default is sky above, ground below",
          "[policies]") {
  auto p = make_planner(
      "hemisphere",
      planner_params_from_cli("hemisphere", {"sky_r=0.2", "sky_g=0.4", "sky_b=1", "ground_r=0.3",
                                             "ground_g=0.2", "ground_b=0.1"}));
  const LookupResult before = p->lookup({0, 0, 0});
  CHECK(before.fell_back);
  // E(theta) = pi (A (1 + cos)/2 + B (1 - cos)/2): the spec's sky/ground oracle, exactly.
  const Rgb sky(0.2f, 0.4f, 1.0f), ground(0.3f, 0.2f, 0.1f);
  for (double cz : {1.0, 0.5, 0.0, -0.3, -1.0}) {
    const glm::dvec3 n(std::sqrt(1.0 - cz * cz), 0.0, cz);
    const Rgb e = sh_irradiance(before.sh, n);
    const Rgb want =
        static_cast<float>(std::numbers::pi) *
        (sky * static_cast<float>((1 + cz) / 2) + ground * static_cast<float>((1 - cz) / 2));
    for (int ch = 0; ch < 3; ++ch) CHECK(e[ch] == Approx(want[ch]).margin(1e-5));
  }

  auto r = p->plan(frame_at(0, 0.1, {0, 0, 0}));
  REQUIRE(r.size() == 1);
  p->started(r[0].tag);
  const Sh9Rgb captured = distinct_sh(3.0f);
  p->deliver(probe_of(r[0], captured, 0.0, 0.5));
  const LookupResult after = p->lookup({50, 50, 50});
  for (int k = 0; k < kShCount; ++k) {
    INFO(k);
    CHECK(after.sh.c[k] == (k == 0 || k == 2 ? captured.c[k] : Rgb(0.0f)));
  }
  CHECK(after.fell_back);
  CHECK(p->plan(frame_at(1, 0.1, {0, 0, 0})).empty());
}

TEST_CASE("nearest requests at the camera only beyond spacing_m, one at a time", "[policies]") {
  auto p = make_planner("nearest");  // spacing 8 m
  const double dt = 1.0 / 30.0;
  std::int64_t f = 0;
  // Before any probe: the default ambient, fell back.
  CHECK(p->lookup({0, 0, 0}).fell_back);
  CHECK(p->lookup({0, 0, 0}).sh == default_ambient_sh());

  auto ctx = frame_at(f++, dt, {0, 0, 0});
  auto first = p->plan(ctx);
  REQUIRE(first.size() == 1);
  CHECK(first[0].position == glm::dvec3(0, 0, 0));
  p->started(first[0].tag);
  p->update(ctx);

  // In flight at the origin: no new request while the camera stays within 8 m of it.
  std::vector<CaptureRequest> second;
  for (double x = 0.5; x <= 12.0; x += 0.5) {
    ctx = frame_at(f++, dt, {x, 0, 0}, /*startable=*/3);
    auto req = p->plan(ctx);
    CHECK(req.size() <= 1);  // never more than one per frame
    if (x <= 8.0) {
      CHECK(req.empty());
    }
    for (const auto& r : req) {
      p->started(r.tag);
      second.push_back(r);
    }
    p->update(ctx);
  }
  // Only the first frame beyond 8 m asked (x = 8.5); the second request then covers the rest.
  REQUIRE(second.size() == 1);
  CHECK(second[0].position == glm::dvec3(8.5, 0, 0));

  // Finished probes count like in-flight ones; a refused request is asked again.
  p->deliver(probe_of(first[0], uniform_sh(Rgb(1, 0, 0)), 0.0, 0.2));
  p->deliver(probe_of(second[0], uniform_sh(Rgb(0, 1, 0)), 0.3, 0.5));
  ctx = frame_at(f++, dt, {4, 0, 0});
  CHECK(p->plan(ctx).empty());
  ctx = frame_at(f++, dt, {20, 0, 0});
  auto third = p->plan(ctx);
  REQUIRE(third.size() == 1);
  p->refused(third[0].tag);
  ctx = frame_at(f++, dt, {20, 0, 0});
  auto again = p->plan(ctx);
  REQUIRE(again.size() == 1);
  CHECK(again[0].tag != third[0].tag);
  // Nothing startable: no request.
  p->refused(again[0].tag);
  CHECK(p->plan(frame_at(f++, dt, {20, 0, 0}, 0)).empty());
}

TEST_CASE("nearest with predict captures one capture latency ahead", "[policies]") {
  auto p = nearest_with({"predict=true"});
  auto ctx = frame_at(0, 0.1, {0, 0, 0});
  ctx.camera_velocity = {10, 0, 0};
  ctx.faces_per_frame = 1.0;  // 6 frames of 0.1 s
  auto r = p->plan(ctx);
  REQUIRE(r.size() == 1);
  CHECK(r[0].position.x == Approx(6.0));
  ctx.faces_per_frame = 4.0;  // ceil(6 / 4) = 2 frames
  auto q = nearest_with({"predict=true"});
  r = q->plan(ctx);
  REQUIRE(r.size() == 1);
  CHECK(r[0].position.x == Approx(2.0));
  ctx.camera_cut = true;  // no prediction across a cut
  auto c = nearest_with({"predict=true"});
  r = c->plan(ctx);
  REQUIRE(r.size() == 1);
  CHECK(r[0].position.x == 0.0);
}

TEST_CASE("nearest fades a new probe in over blend_s", "[policies]") {
  auto p = nearest_with({"blend_s=0.5"});
  const Sh9Rgb red = uniform_sh(Rgb(1, 0, 0)), blue = uniform_sh(Rgb(0, 0, 1));
  const double dt = 0.125;

  auto ctx = frame_at(0, dt, {0, 0, 0});
  auto a = p->plan(ctx);
  REQUIRE(a.size() == 1);
  p->started(a[0].tag);
  p->update(ctx);
  p->deliver(probe_of(a[0], red, 0.0, 0.0));
  // The first probe has nothing to fade from: it is used at once.
  ctx = frame_at(1, dt, {0, 0, 0});
  p->update(ctx);
  CHECK(p->lookup({0, 0, 0}).sh == red);
  CHECK(p->lookup({0, 0, 0}).contributor_count == 1);

  // A second probe at x = 10 arrives at the end of frame 8 (t = 1.0).
  ctx = frame_at(2, dt, {10, 0, 0});
  auto b = p->plan(ctx);
  REQUIRE(b.size() == 1);
  CHECK(b[0].position == glm::dvec3(10, 0, 0));
  p->started(b[0].tag);
  p->update(ctx);
  p->deliver(probe_of(b[0], blue, 0.25, 1.0));

  const glm::dvec3 near_b{9.0, 0, 0}, near_a{2.0, 0, 0};
  // Frame 9 (t = 1.125): usable, faded in 0 %: exactly the old value.
  p->update(frame_at(9, dt, {10, 0, 0}));
  LookupResult r = p->lookup(near_b);
  CHECK(r.sh == red);
  CHECK(r.spacing_m == Approx(1.0));
  // Frame 11 (t = 1.375): half the blend time: the average of old and new.
  p->update(frame_at(11, dt, {10, 0, 0}));
  r = p->lookup(near_b);
  for (int ch = 0; ch < 3; ++ch)
    CHECK(r.sh.c[0][ch] == Approx(0.5f * (red.c[0][ch] + blue.c[0][ch])));
  REQUIRE(r.contributor_count == 2);
  CHECK(r.contributors[0].tag == b[0].tag);
  CHECK(r.contributors[0].weight == Approx(0.5f));
  CHECK(r.contributors[1].tag == a[0].tag);
  CHECK(r.data_time == Approx(0.125));  // halfway between 0.0 and 0.25
  // Points still nearest to the old probe are untouched.
  CHECK(p->lookup(near_a).sh == red);
  // Frame 13 (t = 1.625): the blend is over.
  p->update(frame_at(13, dt, {10, 0, 0}));
  r = p->lookup(near_b);
  CHECK(r.sh == blue);
  CHECK(r.contributor_count == 1);
  p->update(frame_at(14, dt, {10, 0, 0}));
  CHECK(p->lookup(near_b).sh == blue);
}

TEST_CASE("nearest evicts beyond max_probes (farthest first) and after lifetime_s", "[policies]") {
  auto p = nearest_with({"max_probes=3", "lifetime_s=5", "spacing_m=4"});
  const double dt = 0.5;
  std::vector<std::uint64_t> tags;
  std::vector<std::int64_t> bytes;
  for (int i = 0; i < 5; ++i) {  // probes at x = 0, 10, 20, 30, 40, requested at t = 0 .. 2
    auto ctx = frame_at(i, dt, {10.0 * i, 0, 0});
    auto r = p->plan(ctx);
    REQUIRE(r.size() == 1);
    p->started(r[0].tag);
    p->update(ctx);
    p->deliver(probe_of(r[0], uniform_sh(Rgb(static_cast<float>(i))), ctx.time, ctx.time));
    tags.push_back(r[0].tag);
    bytes.push_back(p->stats().bytes);
  }
  CHECK(p->stats().live_probes == 3);
  // 9 x 3 floats per probe at least, and growth per probe while under the cap.
  CHECK(bytes[1] - bytes[0] >= static_cast<std::int64_t>(sizeof(Sh9Rgb)));
  CHECK(bytes[4] == bytes[2]);
  // The camera is at x = 40: the probes at 0 and 10 went. x = 12 is now nearest to 20.
  LookupResult r = p->lookup({12, 0, 0});
  CHECK(r.contributors[0].tag == tags[2]);
  CHECK(r.spacing_m == Approx(8.0));

  // Lifetime counts from the request time; a probe goes once it is older than lifetime_s.
  p->update(frame_at(13, dt, {40, 0, 0}));  // t = 6.5: 20 (t=1.0) expired, 30 (t=1.5) is 5 s old
  CHECK(p->stats().live_probes == 2);
  CHECK(p->lookup({12, 0, 0}).contributors[0].tag == tags[3]);
  p->update(frame_at(14, dt, {40, 0, 0}));  // t = 7.0: 30 expired
  CHECK(p->stats().live_probes == 1);
  CHECK(p->lookup({0, 0, 0}).contributors[0].tag == tags[4]);
  p->update(frame_at(15, dt, {40, 0, 0}));  // t = 7.5: all expired
  CHECK(p->stats().live_probes == 0);
  CHECK(p->lookup({40, 0, 0}).fell_back);
}
