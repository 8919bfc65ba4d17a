// `grid` (scrolling DDGI-style probe grid) driven by hand: scrolling keeps the interior,
// refresh priority, trilinear interpolation, time-based hysteresis, and the window's edges.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "policies/baselines/scrolling_grid.h"
#include "policies/core/default_ambient.h"
#include "policies/registry/registry.h"
#include "sim/planner.h"
#include "sim/sh/sh9.h"

using namespace ambisim;

namespace {

// Flat ground at z = 0.
const WorldQueries& flat_world() {
  static const WorldQueries w = [] {
    WorldQueries q;
    q.ground_height = [](double, double) { return 0.0; };
    q.surface_height = q.ground_height;
    q.bounds_min = {-1000, -1000, -100};
    q.bounds_max = {1000, 1000, 100};
    return q;
  }();
  return w;
}

FrameContext frame_at(double time, glm::dvec3 camera, int startable) {
  FrameContext c;
  c.frame = static_cast<std::int64_t>(std::llround(time * 60.0));
  c.time = time;
  c.dt = 1.0 / 60.0;
  c.camera_position = camera;
  c.startable_captures = startable;
  c.world = &flat_world();
  return c;
}

ScrollingGridPlanner make_grid(const std::vector<std::string>& sets) {
  return ScrollingGridPlanner(planner_params_from_cli("grid", sets));
}

// A set holding `v` in every L0 channel (L0 only, so L1/L2 storage does not matter).
Sh9Rgb flat_sh(float v) {
  Sh9Rgb s;
  s.c[0] = Rgb(v, 2.0f * v, 0.5f * v);
  return s;
}

// One frame that starts every request at once and delivers them at its end with `value_at`.
template <class F>
std::vector<CaptureRequest> capture_all(ScrollingGridPlanner& g, const FrameContext& ctx,
                                        F value_at) {
  const auto req = g.plan(ctx);
  for (const auto& r : req) g.started(r.tag);
  g.update(ctx);
  for (const auto& r : req) {
    g.deliver({r.tag, r.position, value_at(r.position), ctx.time, ctx.time});
  }
  return req;
}

}  // namespace

TEST_CASE("grid: scrolling by one cell keeps the interior and needs one slab", "[baselines]") {
  // Layers at z = 4, 8, 12 (middle = nearest 8 m above the flat ground): all active.
  auto g = make_grid({"nx=5", "ny=5", "nz=3", "spacing_m=8", "vertical_spacing_m=4", "height_m=8"});
  auto first = capture_all(g, frame_at(0.0, {1.0, -2.0, 1.5}, 1000),
                           [](const glm::dvec3&) { return flat_sh(1.0f); });
  CHECK(first.size() == 75);
  CHECK(g.probe_count() == 75);
  CHECK(g.window_min() == ScrollingGridPlanner::Key{-2, -2, 1});
  CHECK(g.window_max() == ScrollingGridPlanner::Key{2, 2, 3});

  // One cell east: the window scrolls by one column; only that slab (5 x 3) is new.
  const auto ctx = frame_at(1.0, {9.0, -2.0, 1.5}, 1000);
  const auto req = g.plan(ctx);
  REQUIRE(req.size() > 15);  // everything is refreshable; the new slab comes first
  for (std::size_t i = 0; i < 15; ++i) CHECK(req[i].position.x == 24.0);
  CHECK(req[15].position.x != 24.0);
  CHECK(g.window_min() == ScrollingGridPlanner::Key{-1, -2, 1});
  std::size_t without = 0;
  for (std::int64_t i = -1; i <= 3; ++i) {
    for (std::int64_t j = -2; j <= 2; ++j) {
      for (std::int64_t k = 1; k <= 3; ++k) without += g.has_data({i, j, k}) ? 0 : 1;
    }
  }
  CHECK(without == 15);
  CHECK(g.has_data({2, 0, 2}));         // interior: kept
  CHECK_FALSE(g.has_data({-2, 0, 2}));  // left the window: dropped
}

TEST_CASE("grid: never-captured first (nearest first), then stale-and-close", "[baselines]") {
  // One row of five probes at x = -16 .. 16, z = 8.
  auto g = make_grid({"nx=5", "ny=1", "nz=1", "spacing_m=8", "vertical_spacing_m=4", "height_m=8"});
  const glm::dvec3 cam{1.0, 0.0, 8.0};  // distances 1, 7, 9, 15, 17
  auto xs = [](const std::vector<CaptureRequest>& r) {
    std::vector<double> out;
    for (const auto& q : r) out.push_back(q.position.x);
    return out;
  };
  // Nothing captured: by distance to the camera.
  CHECK(xs(g.plan(frame_at(0.0, cam, 5))) == std::vector<double>{0, 8, -8, 16, -16});

  auto run = [&](double t, int n) {
    return capture_all(g, frame_at(t, cam, n), [](const glm::dvec3&) { return flat_sh(1.0f); });
  };
  CHECK(xs(run(0.0, 3)) == std::vector<double>{0, 8, -8});
  // At t = 5 the two never-captured probes come first (nearest first), then the captured
  // ones by age / (1 + d / 8), all of age 5: x = 0 (4.44) before 8 (2.67) and -8 (2.35).
  CHECK(xs(run(5.0, 3)) == std::vector<double>{16, -16, 0});
  // At t = 10: x = 8 (age 10: 5.33), -8 (age 10: 4.71), 0 (age 5: 4.44), 16 (1.74),
  // -16 (1.60): the stale one beats the closest one.
  CHECK(xs(g.plan(frame_at(10.0, cam, 5))) == std::vector<double>{8, -8, 0, 16, -16});
}

TEST_CASE("grid: trilinear reproduces a linear field of probes exactly", "[baselines]") {
  auto g = make_grid(
      {"nx=3", "ny=3", "nz=3", "spacing_m=8", "vertical_spacing_m=4", "height_m=8", "blend_s=0"});
  auto field = [](const glm::dvec3& p) {
    return static_cast<float>(2.0 + 0.05 * p.x - 0.03 * p.y + 0.1 * p.z);
  };
  capture_all(g, frame_at(0.0, {0, 0, 1.5}, 1000),
              [&](const glm::dvec3& p) { return flat_sh(field(p)); });
  for (const glm::dvec3& p : {glm::dvec3(3.7, -5.1, 6.3), glm::dvec3(-7.9, 7.9, 11.0),
                              glm::dvec3(0.0, 0.0, 8.0), glm::dvec3(4.0, 2.0, 4.0)}) {
    INFO(p.x << " " << p.y << " " << p.z);
    const LookupResult r = g.lookup(p);
    CHECK_FALSE(r.fell_back);
    CHECK(r.spacing_m == 8.0);
    CHECK(r.sh.c[0].x == Approx(field(p)).epsilon(1e-5));
    CHECK(r.sh.c[0].y == Approx(2.0 * field(p)).epsilon(1e-5));
    REQUIRE(r.contributor_count >= 1);
    float sum = 0.0f;
    for (int i = 0; i < r.contributor_count; ++i) sum += r.contributors[i].weight;
    CHECK(sum == Approx(1.0f));
  }
  CHECK(g.lookup({3.7, -5.1, 6.3}).contributor_count == 8);
  CHECK(g.lookup({0.0, 0.0, 8.0}).contributor_count == 1);  // exactly on a probe
}

TEST_CASE("grid: blending converges with time constant blend_s, whatever the frame rate",
          "[baselines]") {
  for (double fps : {30.0, 144.0}) {
    INFO("fps " << fps);
    auto g = make_grid({"nx=1", "ny=1", "nz=1", "vertical_spacing_m=4", "height_m=8", "blend_s=0.5",
                        "big_change=0.5", "big_change_blend_s=0.1"});
    const glm::dvec3 cam{0, 0, 1.5}, at{0, 0, 8};
    const float a = 1.0f, b = 1.2f, c = 3.0f;
    // The first capture is taken as is.
    capture_all(g, frame_at(0.0, cam, 1), [&](const glm::dvec3&) { return flat_sh(a); });
    CHECK(g.lookup(at).sh == flat_sh(a));

    // A small change (20 %): fades with blend_s from the first update after delivery.
    const double t0 = 1.0;
    auto req = g.plan(frame_at(t0 - 1.0 / fps, cam, 1));
    REQUIRE(req.size() == 1);
    g.started(req[0].tag);
    g.deliver({req[0].tag, req[0].position, flat_sh(b), t0 - 1.0 / fps, t0 - 1.0 / fps});
    CHECK(g.lookup(at).sh == flat_sh(a));  // not usable before the next update
    double t = t0;
    g.update(frame_at(t, cam, 0));
    CHECK(g.lookup(at).sh.c[0].x == Approx(a));
    const int steps = static_cast<int>(std::llround(0.5 * fps));
    for (int i = 0; i < steps; ++i) g.update(frame_at(t += 1.0 / fps, cam, 0));
    const double w = 1.0 - std::exp(-1.0);  // one time constant: 63.2 %
    CHECK(g.lookup(at).sh.c[0].x == Approx(a + w * (b - a)).epsilon(1e-4));
    CHECK(g.lookup(at).data_time == Approx((t0 - 1.0 / fps) * w).epsilon(1e-4));
    while (t < t0 + 2.6) g.update(frame_at(t += 1.0 / fps, cam, 0));
    CHECK(g.lookup(at).sh == flat_sh(b));  // after 5 time constants: the target, exactly

    // A big change (x 2.5) uses big_change_blend_s = 0.1.
    req = g.plan(frame_at(t, cam, 1));
    REQUIRE(req.size() == 1);
    g.started(req[0].tag);
    g.deliver({req[0].tag, req[0].position, flat_sh(c), t, t});
    g.update(frame_at(t += 1.0 / fps, cam, 0));
    const double t1 = t;
    while (t < t1 + 0.1 - 1e-9) g.update(frame_at(t += 1.0 / fps, cam, 0));
    const double wb = 1.0 - std::exp(-(t - t1) / 0.1);
    CHECK(g.lookup(at).sh.c[0].x == Approx(b + wb * (c - b)).epsilon(1e-4));
  }
}

TEST_CASE("grid: lookups outside the window clamp to its edge and fall back", "[baselines]") {
  auto g = make_grid(
      {"nx=3", "ny=3", "nz=1", "spacing_m=8", "vertical_spacing_m=4", "height_m=8", "blend_s=0"});
  // Before any data: the default ambient, fell back, no contributors.
  LookupResult none = g.lookup({0, 0, 8});
  CHECK(none.fell_back);
  CHECK(none.sh == default_ambient_sh());
  CHECK(none.contributor_count == 0);
  CHECK(std::isinf(none.spacing_m));

  capture_all(g, frame_at(0.0, {0, 0, 1.5}, 1000),
              [](const glm::dvec3& p) { return flat_sh(static_cast<float>(10.0 + p.x)); });
  // 30 m east of the window's edge (x = 8) at the probes' height: the edge probes' value,
  // fell_back, spacing = 8 + 30.
  const LookupResult out = g.lookup({38.0, 0.0, 8.0});
  CHECK(out.fell_back);
  CHECK(out.spacing_m == Approx(38.0));
  CHECK(out.contributor_count == 1);
  CHECK(out.sh.c[0].x == Approx(18.0f));
  // Inside the footprint but 3 m below the single layer: clamped vertically, fell back.
  const LookupResult below = g.lookup({4.0, 0.0, 5.0});
  CHECK(below.fell_back);
  CHECK(below.spacing_m == Approx(11.0));
  CHECK(below.sh.c[0].x == Approx(14.0f));
  // Inside: served.
  CHECK_FALSE(g.lookup({4.0, 0.0, 8.0}).fell_back);
}

TEST_CASE("grid: a cell without data answers with the nearest probe, as a fallback",
          "[baselines]") {
  auto g = make_grid({"nx=5", "ny=1", "nz=1", "spacing_m=8", "vertical_spacing_m=4", "height_m=8",
                      "big_change=0"});
  // Only the probe nearest the camera (x = 0) is captured.
  capture_all(g, frame_at(0.0, {0, 0, 8}, 1), [](const glm::dvec3&) { return flat_sh(3.0f); });
  const LookupResult in_cell = g.lookup({4.0, 0.0, 8.0});  // its own cell: served
  CHECK_FALSE(in_cell.fell_back);
  CHECK(in_cell.sh == flat_sh(3.0f));
  const LookupResult far = g.lookup({13.0, 0.0, 8.0});  // cell 8..16: no data
  CHECK(far.fell_back);
  CHECK(far.contributor_count == 1);
  CHECK(far.spacing_m == Approx(13.0));
  CHECK(far.sh == flat_sh(3.0f));
  // A first capture there fades in from that fallback value instead of popping.
  const auto req = g.plan(frame_at(1.0, {16, 0, 8}, 1));
  REQUIRE(req.size() == 1);
  CHECK(req[0].position == glm::dvec3(16, 0, 8));
  g.started(req[0].tag);
  g.deliver({req[0].tag, req[0].position, flat_sh(1.0f), 1.0, 1.1});
  g.update(frame_at(1.1, {16, 0, 8}, 0));
  CHECK(g.lookup({16.0, 0.0, 8.0}).sh.c[0].x == Approx(3.0f));
  g.update(frame_at(1.6, {16, 0, 8}, 0));
  CHECK(g.lookup({16.0, 0.0, 8.0}).sh.c[0].x == Approx(3.0 - 2.0 * (1.0 - std::exp(-1.0))));
}

TEST_CASE("grid: probes in the terrain move up by half a layer at most, or are never captured",
          "[baselines]") {
  // 2 m layers, the middle one nearest the ground (height_m = 0) over flat ground: z = -2, 0,
  // 2. z = 0 is 0.25 m short of the clearance: captured 0.25 m up (DDGI relocation, within half
  // a layer); z = -2 would have to move 2.25 m: inactive (classification).
  auto g = make_grid({"nx=3", "ny=3", "blend_s=0", "height_m=0"});
  const auto req = capture_all(g, frame_at(0.0, {0, 0, 1.5}, 1000),
                               [](const glm::dvec3& p) { return flat_sh(1.0f + 0.5f * p.z); });
  CHECK(req.size() == 18);
  int relocated = 0;
  for (const auto& r : req) {
    CHECK((r.position.z == 2.0 || r.position.z == ScrollingGridPlanner::kClearance_m));
    relocated += r.position.z < 1.0 ? 1 : 0;
  }
  CHECK(relocated == 9);
  CHECK(g.window_min()[2] == -1);
  CHECK(g.dropped_in_solids() == 9);
  // A receiver 1 m above the ground interpolates both layers, the relocated one standing for
  // its lattice point: (1 + 0.5 * 0.25) / 2 + 2 / 2.
  const LookupResult r = g.lookup({3.0, 1.0, 1.0});
  CHECK_FALSE(r.fell_back);
  CHECK(r.contributor_count == 8);
  CHECK(r.sh.c[0].x == Approx(0.5 * (1.0 + 0.5 * 0.25) + 0.5 * 2.0));
  PlannerStats s = g.stats();
  CHECK(s.live_probes == 18);
  CHECK(s.nodes == 18);
  CHECK(s.bytes >= 18 * 108);
  std::vector<ProbeNodeView> nodes;
  g.describe_nodes(nodes);
  CHECK(nodes.size() == 18);
}

TEST_CASE("grid: fp16 L1 storage costs a quarter of the bytes per set", "[baselines]") {
  auto full =
      make_grid({"nx=3", "ny=3", "nz=1", "height_m=8", "vertical_spacing_m=4", "blend_s=0"});
  auto small = make_grid({"nx=3", "ny=3", "nz=1", "height_m=8", "vertical_spacing_m=4", "order=L1",
                          "precision=fp16", "blend_s=0"});
  Sh9Rgb rich;
  for (int k = 0; k < kShCount; ++k) rich.c[k] = Rgb(0.1f * k + 0.1f, 0.3f, 0.7f);
  capture_all(full, frame_at(0.0, {0, 0, 1.5}, 100), [&](const glm::dvec3&) { return rich; });
  capture_all(small, frame_at(0.0, {0, 0, 1.5}, 100), [&](const glm::dvec3&) { return rich; });
  CHECK(full.stats().bytes - small.stats().bytes == 9 * (108 - 24));
  CHECK(small.lookup({0, 0, 8}).sh.c[4].x == 0.0f);  // L2 dropped
  CHECK(full.lookup({0, 0, 8}).sh.c[4].x == Approx(0.5f));
}
