// `cascades` (scrolling clipmaps) driven by hand: doubling levels, scrolling by whole cells,
// shared captures across levels, refresh order, DDGI hysteresis against its closed form, the
// brightness clamp, probe validity on the forest edge, exact lookups, and levels=1 == grid.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include "policies/baselines/cascades.h"
#include "policies/baselines/scrolling_grid.h"
#include "policies/core/default_ambient.h"
#include "policies/registry/registry.h"
#include "sim/planner.h"
#include "sim/render/capture.h"
#include "sim/run/simulator.h"
#include "sim/scenario/scenario_motion.h"
#include "sim/sh/sh9.h"
#include "sim/world/world_queries.h"
#include "tests/support/scenario_fixtures.h"

using namespace ambisim;

namespace {

using Key = CascadesPlanner::Key;

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

FrameContext frame_at(double time, glm::dvec3 camera, int startable, double fps = 60.0) {
  FrameContext c;
  c.frame = static_cast<std::int64_t>(std::llround(time * fps));
  c.time = time;
  c.dt = 1.0 / fps;
  c.camera_position = camera;
  c.startable_captures = startable;
  c.world = &flat_world();
  return c;
}

CascadesPlanner make_cascades(const std::vector<std::string>& sets) {
  return CascadesPlanner(planner_params_from_cli("cascades", sets));
}

// A set holding `v` in every L0 channel (L0 only, so L1/L2 storage does not matter).
Sh9Rgb tinted_sh(float v) {
  Sh9Rgb s;
  s.c[0] = Rgb(v, 2.0f * v, 0.5f * v);
  return s;
}

// One frame that starts every request at once and delivers them at its end with `value_at`.
template <class P, class F>
std::vector<CaptureRequest> capture_all(P& g, const FrameContext& ctx, F value_at) {
  const auto req = g.plan(ctx);
  for (const auto& r : req) g.started(r.tag);
  g.update(ctx);
  for (const auto& r : req) {
    g.deliver({r.tag, r.position, value_at(r.position), ctx.time, ctx.time});
  }
  return req;
}

}  // namespace

TEST_CASE("cascades: each level doubles both spacings and holds its window around the camera",
          "[baselines][cascades]") {
  auto g =
      make_cascades({"levels=4", "nx=7", "ny=5", "nz=3", "spacing_m=4", "vertical_spacing_m=2"});
  REQUIRE(g.level_count() == 4);
  const glm::dvec3 cam{37.0, -21.0, 1.5};
  g.plan(frame_at(0.0, cam, 0));
  for (int l = 0; l < 4; ++l) {
    INFO("level " << l);
    CHECK(g.spacing_of(l) == 4.0 * std::pow(2.0, l));
    CHECK(g.vertical_spacing_of(l) == 2.0 * std::pow(2.0, l));
    const Key lo = g.window_min(l), hi = g.window_max(l);
    CHECK(hi[0] - lo[0] == 6);
    CHECK(hi[1] - lo[1] == 4);
    CHECK(hi[2] - lo[2] == 2);
    // Centred on the level's lattice point nearest the camera.
    const double s = g.spacing_of(l);
    CHECK(lo[0] + 3 == std::llround(cam.x / s));
    CHECK(lo[1] + 2 == std::llround(cam.y / s));
    // Middle layer: the level's lattice height nearest 1.5 m above the flat ground.
    CHECK(lo[2] + 1 == std::llround(1.5 / g.vertical_spacing_of(l)));
    if (l > 0) {  // each window covers the finer one horizontally
      const double sf = g.spacing_of(l - 1);
      CHECK(static_cast<double>(lo[0]) * s <= static_cast<double>(g.window_min(l - 1)[0]) * sf);
      CHECK(static_cast<double>(hi[0]) * s >= static_cast<double>(g.window_max(l - 1)[0]) * sf);
      CHECK(static_cast<double>(lo[1]) * s <= static_cast<double>(g.window_min(l - 1)[1]) * sf);
      CHECK(static_cast<double>(hi[1]) * s >= static_cast<double>(g.window_max(l - 1)[1]) * sf);
    }
  }
}

TEST_CASE("cascades: levels scroll by whole cells of their own, keeping their data",
          "[baselines][cascades]") {
  // Level 0: 8 m / 4 m, layers z = 4, 8, 12; level 1: 16 m / 8 m, layers z = 0, 8, 16 (z = 0
  // is relocated to the 0.25 m clearance).
  auto g = make_cascades({"levels=2", "nx=5", "ny=5", "nz=3", "spacing_m=8", "vertical_spacing_m=4",
                          "height_m=8", "hysteresis=0"});
  auto by_height = [](const glm::dvec3& p) {
    return tinted_sh(static_cast<float>(1.0 + 0.01 * p.z));
  };
  const auto first = capture_all(g, frame_at(0.0, {-3.0, 0.0, 1.5}, 1000), by_height);
  // 75 + 75 probes; the 9 level-1 points at z = 8 inside level 0's footprint share a capture.
  CHECK(g.probe_count(0) == 75);
  CHECK(g.probe_count(1) == 75);
  CHECK(first.size() == 141);
  CHECK(g.capture_point(1, {0, 0, 0}) == glm::dvec3(0.0, 0.0, 0.25));
  CHECK(g.relocated_count() == 25);
  CHECK(g.has_data(1, {1, 1, 1}));  // (16, 16, 8): fed by level 0's capture there
  CHECK(g.value(1, {1, 1, 1}) == g.value(0, {2, 2, 2}));
  CHECK(g.window_min(0) == Key{-2, -2, 1});
  CHECK(g.window_min(1) == Key{-2, -2, 0});

  // 8 m east: level 0 scrolls by one cell (round(5 / 8) = 1), level 1 not (round(5 / 16) = 0).
  const auto req = g.plan(frame_at(1.0, {5.0, 0.0, 1.5}, 1000));
  CHECK(g.window_min(0) == Key{-1, -2, 1});
  CHECK(g.window_max(0) == Key{3, 2, 3});
  CHECK(g.window_min(1) == Key{-2, -2, 0});
  REQUIRE(req.size() > 15);
  for (std::size_t i = 0; i < 15; ++i) CHECK(req[i].position.x == 24.0);  // the new slab first
  CHECK(req[15].position.x != 24.0);
  std::size_t without = 0;
  for (std::int64_t i = -1; i <= 3; ++i) {
    for (std::int64_t j = -2; j <= 2; ++j) {
      for (std::int64_t k = 1; k <= 3; ++k) without += g.has_data(0, {i, j, k}) ? 0 : 1;
    }
  }
  CHECK(without == 15);
  CHECK(g.value(0, {2, 0, 2}) == by_height({16.0, 0.0, 8.0}));  // interior: kept
  CHECK_FALSE(g.is_active(0, {-2, 0, 2}));                      // left the window: dropped
  CHECK(g.probe_count(1) == 75);
  CHECK(g.has_data(1, {-2, 0, 1}));  // level 1 did not move

  // Stats and views count both levels.
  CHECK(g.stats().nodes == 150);
  CHECK(g.stats().live_probes == 135);
  std::vector<ProbeNodeView> nodes;
  g.describe_nodes(nodes);
  CHECK(nodes.size() == 150);
  CHECK(std::count_if(nodes.begin(), nodes.end(), [](const auto& v) { return v.depth == 1; }) ==
        75);
}

TEST_CASE("cascades: never-captured first (nearest first), then stale-and-close",
          "[baselines][cascades]") {
  // grid's own case, one level: one row of five probes at x = -16 .. 16, z = 8.
  auto g = make_cascades(
      {"levels=1", "nx=5", "ny=1", "nz=1", "spacing_m=8", "vertical_spacing_m=4", "height_m=8"});
  const glm::dvec3 cam{1.0, 0.0, 8.0};  // distances 1, 7, 9, 15, 17
  auto xs = [](const std::vector<CaptureRequest>& r) {
    std::vector<double> out;
    for (const auto& q : r) out.push_back(q.position.x);
    return out;
  };
  CHECK(xs(g.plan(frame_at(0.0, cam, 5))) == std::vector<double>{0, 8, -8, 16, -16});
  auto run = [&](double t, int n) {
    return capture_all(g, frame_at(t, cam, n), [](const glm::dvec3&) { return tinted_sh(1.0f); });
  };
  CHECK(xs(run(0.0, 3)) == std::vector<double>{0, 8, -8});
  // t = 5: the two never-captured ones (nearest first), then x = 0 (age 5 / (1 + 1/8)).
  CHECK(xs(run(5.0, 3)) == std::vector<double>{16, -16, 0});
  // t = 10: 8 (10 / 1.875 = 5.33), -8 (4.71), 0 (5 / 1.125 = 4.44), 16 (1.74), -16 (1.60).
  CHECK(xs(g.plan(frame_at(10.0, cam, 5))) == std::vector<double>{8, -8, 0, 16, -16});
  // Never more than the startable captures, never more than the candidates.
  CHECK(g.plan(frame_at(11.0, cam, 2)).size() == 2);
  CHECK(g.plan(frame_at(12.0, cam, 50)).size() == 5);
  CHECK(g.plan(frame_at(13.0, cam, 0)).empty());

  // Two levels: a coarse probe never captured beats every refresh of the finer level.
  auto h = make_cascades(
      {"levels=2", "nx=3", "ny=1", "nz=1", "spacing_m=8", "vertical_spacing_m=4", "height_m=8"});
  // Level 0: x = -8, 0, 8 at z = 8; level 1: x = -16, 0, 16 at z = 8 (0 shared).
  const auto a =
      capture_all(h, frame_at(0.0, cam, 3), [](const glm::dvec3&) { return tinted_sh(1.0f); });
  CHECK(xs(a) == std::vector<double>{0, 8, -8});
  CHECK(xs(h.plan(frame_at(20.0, cam, 3))) == std::vector<double>{16, -16, 0});
}

TEST_CASE("cascades: DDGI hysteresis follows its closed form at any frame rate",
          "[baselines][cascades]") {
  for (double fps : {30.0, 60.0, 144.0}) {
    INFO("fps " << fps);
    auto g =
        make_cascades({"levels=1", "nx=1", "ny=1", "nz=1", "vertical_spacing_m=4", "height_m=8"});
    const glm::dvec3 cam{0, 0, 1.5}, at{0, 0, 8};
    const float a = 1.0f, b = 1.2f, c = 0.5f;
    // The first capture is taken as is (no hysteresis on a never-captured probe).
    capture_all(g, frame_at(0.0, cam, 1, fps), [&](const glm::dvec3&) { return tinted_sh(a); });
    CHECK(g.lookup(at).sh == tinted_sh(a));

    // A small change (20 %, under the 0.25 threshold): value = b + (a - b) 0.97^(60 t).
    double t = 1.0;
    auto req = g.plan(frame_at(t, cam, 1, fps));
    REQUIRE(req.size() == 1);
    g.started(req[0].tag);
    g.update(frame_at(t, cam, 1, fps));
    g.deliver({req[0].tag, req[0].position, tinted_sh(b), t, t});
    CHECK(g.lookup(at).sh == tinted_sh(a));  // usable from the next update
    const double t0 = t;
    const int steps = static_cast<int>(std::llround(0.5 * fps));
    for (int i = 0; i < steps; ++i) g.update(frame_at(t += 1.0 / fps, cam, 0, fps));
    const double keep = std::pow(0.97, 60.0 * (t - t0));
    CHECK(g.lookup(at).sh.c[0].x == Approx(b + (a - b) * keep).epsilon(1e-4));
    CHECK(g.lookup(at).sh.c[0].y == Approx(2.0 * (b + (a - b) * keep)).epsilon(1e-4));
    CHECK(g.lookup(at).data_time == Approx(t0 * (1.0 - keep)).epsilon(1e-4));
    // The time constant is -1 / (60 ln 0.97) = 0.547 s: 63.2 % after it.
    const double tau = -1.0 / (60.0 * std::log(0.97));
    CHECK(tau == Approx(0.5472).epsilon(1e-3));
    // It snaps to the target once 99.3 % of the way is done (5 time constants).
    while (t < t0 + 5.0 * tau + 0.05) g.update(frame_at(t += 1.0 / fps, cam, 0, fps));
    CHECK(g.lookup(at).sh == tinted_sh(b));
    CHECK(g.stats().live_probes == 1);

    // A big change (darkening by 58 %): the hysteresis drops to 0.97 - 0.75 = 0.22.
    req = g.plan(frame_at(t, cam, 1, fps));
    REQUIRE(req.size() == 1);
    g.started(req[0].tag);
    g.update(frame_at(t, cam, 1, fps));
    g.deliver({req[0].tag, req[0].position, tinted_sh(c), t, t});
    CHECK(g.stats().live_probes == 2);  // value and target while it blends
    g.update(frame_at(t += 1.0 / fps, cam, 0, fps));
    const double k1 = std::pow(0.22, 60.0 / fps);
    CHECK(g.lookup(at).sh.c[0].x == Approx(c + (b - c) * k1).epsilon(1e-5));
  }
}

TEST_CASE("cascades: the brightness clamp limits brightening to 10 % per 60 Hz frame",
          "[baselines][cascades]") {
  for (double fps : {60.0, 30.0}) {
    INFO("fps " << fps);
    for (bool clamp : {true, false}) {
      INFO("clamp " << clamp);
      auto g =
          make_cascades({"levels=1", "nx=1", "ny=1", "nz=1", "vertical_spacing_m=4", "height_m=8",
                         clamp ? "brightness_threshold=0.1" : "brightness_threshold=0"});
      const glm::dvec3 cam{0, 0, 1.5}, at{0, 0, 8};
      capture_all(g, frame_at(0.0, cam, 1, fps), [](const glm::dvec3&) { return tinted_sh(1.0f); });
      double t = 1.0;
      const auto req = g.plan(frame_at(t, cam, 1, fps));
      REQUIRE(req.size() == 1);
      g.started(req[0].tag);
      g.update(frame_at(t, cam, 1, fps));
      g.deliver({req[0].tag, req[0].position, tinted_sh(10.0f), t, t});  // x 10: a big change
      // Big change (x 10): h = 0.22 while the change left is over 25 %; clamped, a step raises the
      // value by at most 10 % per 60 Hz frame; a blend snaps once less than exp(-5) of the way is
      // left.
      double expect = 1.0, left = 1.0;
      for (int i = 1; i <= 4; ++i) {
        g.update(frame_at(t += 1.0 / fps, cam, 0, fps));
        // The big-change rule is judged at every update (RTXGI: per blending pass).
        const double h = (10.0 - expect) / expect > 0.25 ? 0.22 : 0.97;
        double f = 1.0 - std::pow(h, 60.0 / fps);
        if (clamp) f = std::min(f, expect * (std::pow(1.1, 60.0 / fps) - 1.0) / (10.0 - expect));
        left *= 1.0 - f;
        expect = left < std::exp(-5.0) ? 10.0 : expect + f * (10.0 - expect);
        INFO("frame " << i);
        CHECK(g.lookup(at).sh.c[0].x == Approx(expect).epsilon(1e-5));
      }
      if (clamp) {
        CHECK(expect == Approx(std::pow(1.1, 4 * 60.0 / fps)).epsilon(1e-9));  // it bound
      } else {
        CHECK(expect > 8.0);  // 1 + 0.78 x 9 after the first 60 Hz frame
      }
    }
  }
}

TEST_CASE("cascades: no capture point inside the terrain or the canopy", "[baselines][cascades]") {
  // The forest edge (canopy 15-25 m high with sharp edges) and the motorway (cuttings), 20 s of
  // each route, every probe of every window asked for at once.
  for (const std::string name : {"forest_edge", "motorway"}) {
    INFO(name);
    const auto scenarios = test::short_scenarios(20.0);
    const auto sc = std::find_if(scenarios.begin(), scenarios.end(),
                                 [&](const Scenario& s) { return s.name == name; });
    REQUIRE(sc != scenarios.end());
    const World& world = test::world_for(*sc);
    WorldQueries queries = planner_world_queries(world);
    std::vector<glm::dvec3> route;
    {
      ScenarioMotion motion(*sc, world);
      route = camera_route(motion, 10.0);
    }
    REQUIRE(route.size() > 5);
    auto g = make_cascades({});
    std::int64_t requests = 0, below = 0, lifted = 0;
    double t = 0.0;
    for (const auto& cam : route) {
      FrameContext ctx = frame_at(t += 1.0, cam, 100000);
      ctx.world = &queries;
      for (const auto& r : g.plan(ctx)) {
        ++requests;
        if (r.position.z < queries.surface_height(r.position.x, r.position.y) + 0.25 - 1e-9) {
          ++below;
        }
        if (capture_origin(world, r.position) != r.position) ++lifted;
      }
    }
    INFO(requests << " requests, " << g.relocated_count() << " relocated, "
                  << g.faces_saved_by_inactive() << " faces saved");
    CHECK(requests > 1000);
    CHECK(below == 0);
    CHECK(lifted == 0);
    CHECK(g.relocated_count() > 0);
    CHECK(g.faces_saved_by_inactive() > 0);
    CHECK(g.faces_saved_by_inactive() % 6 == 0);
    // And every active probe of every level is in free air, moved at most 0.45 of a cell.
    for (int l = 0; l < g.level_count(); ++l) {
      const Key lo = g.window_min(l), hi = g.window_max(l);
      for (Key k{lo[0], 0, 0}; k[0] <= hi[0]; ++k[0]) {
        for (k[1] = lo[1]; k[1] <= hi[1]; ++k[1]) {
          for (k[2] = lo[2]; k[2] <= hi[2]; ++k[2]) {
            const auto p = g.capture_point(l, k);
            if (!p) continue;
            CHECK(p->z >= queries.surface_height(p->x, p->y) + 0.25 - 1e-9);
            CHECK(p->z - g.lattice_point(l, k).z <= 0.45 * g.vertical_spacing_of(l) + 1e-9);
            CHECK(p->z >= g.lattice_point(l, k).z);
          }
        }
      }
    }
  }
}

TEST_CASE("cascades: trilinear reproduces a linear field exactly, blended levels too",
          "[baselines][cascades]") {
  // Level 0: 8 m / 4 m, layers 8, 12, 16; level 1: 16 m / 8 m, layers 8, 16, 24 (height 12).
  auto g = make_cascades({"levels=2", "nx=5", "ny=5", "nz=3", "spacing_m=8", "vertical_spacing_m=4",
                          "height_m=12", "hysteresis=0", "blend_cells=0.5"});
  auto field = [](const glm::dvec3& p) {
    return static_cast<float>(2.0 + 0.05 * p.x - 0.03 * p.y + 0.1 * p.z);
  };
  capture_all(g, frame_at(0.0, {0, 0, 1.5}, 1000),
              [&](const glm::dvec3& p) { return tinted_sh(field(p)); });
  CHECK(g.relocated_count() == 0);
  struct Case {
    glm::dvec3 p;
    double spacing;
  };
  for (const Case& c : {Case{{3.7, -5.1, 10.3}, 8.0}, Case{{-7.9, 7.9, 15.0}, 8.0},
                        Case{{0.0, 0.0, 12.0}, 8.0}, Case{{12.0, 2.0, 9.0}, 8.0},
                        // 0.25 cells from level 0's east edge: half of each level.
                        Case{{14.0, 2.0, 12.0}, 12.0},
                        // Beyond level 0 (x > 16), inside level 1.
                        Case{{20.0, -3.0, 14.0}, 16.0},
                        // Above level 0 (z > 16), inside level 1.
                        Case{{1.0, 1.0, 20.0}, 16.0}}) {
    INFO(c.p.x << " " << c.p.y << " " << c.p.z);
    const LookupResult r = g.lookup(c.p);
    CHECK_FALSE(r.fell_back);
    CHECK(r.spacing_m == Approx(c.spacing));
    CHECK(r.sh.c[0].x == Approx(field(c.p)).epsilon(1e-5));
    CHECK(r.sh.c[0].y == Approx(2.0 * field(c.p)).epsilon(1e-5));
    REQUIRE(r.contributor_count >= 1);
    REQUIRE(r.contributor_count <= 8);
    float sum = 0.0f;
    for (int i = 0; i < r.contributor_count; ++i) sum += r.contributors[i].weight;
    CHECK(sum == Approx(1.0f));
  }
  CHECK(g.lookup({3.7, -5.1, 10.3}).contributor_count == 8);
  CHECK(g.lookup({0.0, 0.0, 12.0}).contributor_count == 1);  // exactly on a probe
  // Outside every window: clamped to the coarsest one's box, fell back.
  const LookupResult out = g.lookup({62.0, 0.0, 16.0});  // level 1 ends at x = 32
  CHECK(out.fell_back);
  CHECK(out.spacing_m == Approx(16.0 + 30.0));
  CHECK(out.sh.c[0].x == Approx(field({32.0, 0.0, 16.0})).epsilon(1e-5));
}

TEST_CASE("cascades: with one level it behaves as grid (a single volume)",
          "[baselines][cascades]") {
  const std::vector<std::string> common = {
      "nx=5", "ny=4", "nz=3", "spacing_m=8", "vertical_spacing_m=4", "height_m=8"};
  auto grid_sets = common, casc_sets = common;
  for (const char* s : {"blend_s=0", "big_change=0"}) grid_sets.push_back(s);
  for (const char* s : {"levels=1", "hysteresis=0", "brightness_threshold=0"})
    casc_sets.push_back(s);
  ScrollingGridPlanner grid(planner_params_from_cli("grid", grid_sets));
  auto casc = make_cascades(casc_sets);

  auto value_at = [](const glm::dvec3& p, double t) {
    Sh9Rgb s;
    for (int k = 0; k < kShCount; ++k) {
      s.c[k] = Rgb(static_cast<float>(1.0 + 0.01 * p.x + 0.1 * k + std::sin(t)),
                   static_cast<float>(0.5 + 0.02 * p.y), static_cast<float>(0.2 + 0.03 * p.z));
    }
    return s;
  };
  struct InFlight {
    CaptureRequest r;
    double t;
  };
  std::vector<InFlight> fg, fc;  // delivered two frames after the start
  std::int64_t requests = 0, compared = 0;
  for (int f = 0; f < 240; ++f) {
    const double t = f / 60.0;
    // Diagonal at 40 m/s with a turn: scrolls along both axes.
    const glm::dvec3 cam{0.7 * f - 0.002 * f * f, 0.4 * f, 1.5};
    const FrameContext ctx = frame_at(t, cam, 1 + f % 3);
    const auto rg = grid.plan(ctx);
    const auto rc = casc.plan(ctx);
    REQUIRE(rg.size() == rc.size());
    for (std::size_t i = 0; i < rg.size(); ++i) CHECK(rg[i].position == rc[i].position);
    requests += static_cast<std::int64_t>(rg.size());
    for (const auto& r : rg) {
      grid.started(r.tag);
      fg.push_back({r, t});
    }
    for (const auto& r : rc) {
      casc.started(r.tag);
      fc.push_back({r, t});
    }
    grid.update(ctx);
    casc.update(ctx);
    CHECK(grid.window_min() == casc.window_min(0));
    for (int i = 0; i < 9; ++i) {
      const glm::dvec3 p = cam + glm::dvec3(-30.0 + 7.5 * i, 17.0 - 4.0 * i, -1.0 + 1.6 * i);
      const LookupResult a = grid.lookup(p), b = casc.lookup(p);
      CHECK(a.sh == b.sh);
      CHECK(a.fell_back == b.fell_back);
      CHECK(a.spacing_m == Approx(b.spacing_m));
      CHECK(a.contributor_count == b.contributor_count);
      CHECK(a.data_time == Approx(b.data_time));
      ++compared;
    }
    auto deliver = [&](auto& planner, std::vector<InFlight>& q) {
      while (!q.empty() && q.front().t <= t - 2.0 / 60.0 + 1e-9) {
        const auto& x = q.front();
        planner.deliver({x.r.tag, x.r.position, value_at(x.r.position, x.t), x.t, t});
        q.erase(q.begin());
      }
    };
    deliver(grid, fg);
    deliver(casc, fc);
  }
  CHECK(requests > 300);
  CHECK(compared == 240 * 9);
}

TEST_CASE("cascades: with fade_in a first capture blends in from the lookup it replaces",
          "[baselines][cascades]") {
  for (bool fade : {false, true}) {
    INFO("fade_in " << fade);
    // Two probes, x = 0 and 8 at z = 8 (camera at x = 1: x = 0 is captured first).
    auto g =
        make_cascades({"levels=1", "nx=2", "ny=1", "nz=1", "spacing_m=8", "vertical_spacing_m=4",
                       "height_m=8", fade ? "fade_in=true" : "fade_in=false"});
    const glm::dvec3 cam{1, 0, 1.5}, at{8, 0, 8};
    capture_all(g, frame_at(0.0, cam, 1), [](const glm::dvec3&) { return tinted_sh(3.0f); });
    CHECK(g.lookup(at).sh == tinted_sh(3.0f));  // its cell's one corner with data
    const auto req =
        capture_all(g, frame_at(1.0, cam, 1), [](const glm::dvec3&) { return tinted_sh(2.8f); });
    REQUIRE(req.size() == 1);
    CHECK(req[0].position == glm::dvec3(8, 0, 8));
    CHECK(g.lookup(at).sh == (fade ? tinted_sh(3.0f) : tinted_sh(2.8f)));
    double t = 1.0;
    for (int i = 0; i < 30; ++i) g.update(frame_at(t += 1.0 / 60.0, cam, 0));
    const double expect = fade ? 2.8 + 0.2 * std::pow(0.97, 30.0) : 2.8;
    CHECK(g.lookup(at).sh.c[0].x == Approx(expect).epsilon(1e-4));
  }
}
