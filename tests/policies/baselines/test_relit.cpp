// `relit`: captured once, relit every frame from the current sun and sky. Closed forms on a
// probe whose upper hemisphere sees a uniform sky A at visibility v and whose lower hemisphere
// sees ground of radiance B (hemisphere_sh(v A, B)): the sky term is v S, the bounce
// hemisphere_sh(0, B) scaled by g = G(t) / G0 (G: an unshadowed horizontal plane's irradiance,
// pi A + E_sun sin(elevation) under that sky). Then the simulator: it never recaptures for
// lighting, and where the world's light does not change it answers exactly what `nearest` does.
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <numbers>

#include "policies/baselines/relit.h"
#include "policies/core/default_ambient.h"
#include "policies/registry/registry.h"
#include "sim/base/json_reader.h"
#include "sim/metrics/metrics.h"
#include "sim/run/reference_track.h"
#include "sim/run/run_output.h"
#include "sim/run/simulator.h"
#include "sim/scenario/scenario.h"
#include "sim/world/world.h"

using namespace ambisim;

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// A set whose 27 values are all different and non-zero.
Sh9Rgb distinct_sh(float base) {
  Sh9Rgb s;
  for (int k = 0; k < kShCount; ++k) {
    s.c[k] = Rgb(base + 0.1f * k, base + 0.1f * k + 0.03f, base + 0.1f * k + 0.07f);
  }
  return s;
}

// A uniform sky of radiance `sky` above the horizon (zero below) and a sun of irradiance `sun`
// at `elevation_deg` toward the north.
LightingInfo light_of(Rgb sky, Rgb sun, double elevation_deg) {
  LightingInfo l;
  l.sky_sh = hemisphere_sh(sky, Rgb(0.0f));
  l.sun_dir = {0.0, std::cos(elevation_deg * kDeg), std::sin(elevation_deg * kDeg)};
  l.sun_on = elevation_deg > 0.0;
  l.sun_irradiance = l.sun_on ? sun : Rgb(0.0f);
  return l;
}

LightingInfo scaled(LightingInfo l, float k) {
  l.sky_sh *= k;
  l.sun_irradiance *= k;
  return l;
}

// A planner and a world whose light is `light(t)`, driven as the simulator drives it.
struct Rig {
  std::function<LightingInfo(double)> light;
  WorldQueries world;
  std::unique_ptr<Planner> planner;
  double dt = 1.0 / 60.0;
  std::int64_t frame = 0;

  explicit Rig(std::function<LightingInfo(double)> l, const std::vector<std::string>& sets = {},
               bool static_light = false)
      : light(std::move(l)) {
    world.lighting_static = static_light;
    world.lighting = [this](double t) { return light(t); };
    planner = make_planner("relit", planner_params_from_cli("relit", sets));
  }
  FrameContext ctx(glm::dvec3 camera) const {
    FrameContext c;
    c.frame = frame;
    c.time = static_cast<double>(frame) * dt;
    c.dt = dt;
    c.camera_position = camera;
    c.startable_captures = 1;
    c.world = &world;
    return c;
  }
  // One frame: plan, start, update; every capture is delivered at once (requested and finished
  // this frame) with the radiance `capture` gives for it. Returns the requests.
  std::vector<CaptureRequest> step(glm::dvec3 camera,
                                   const std::function<Sh9Rgb(const CaptureRequest&)>& capture) {
    const FrameContext c = ctx(camera);
    const auto req = planner->plan(c);
    for (const auto& r : req) planner->started(r.tag);
    planner->update(c);
    for (const auto& r : req) planner->deliver({r.tag, r.position, capture(r), c.time, c.time});
    ++frame;
    return req;
  }
  // A frame without captures (the time moves, the light is relit).
  void idle(glm::dvec3 camera) {
    FrameContext c = ctx(camera);
    c.startable_captures = 0;
    planner->plan(c);
    planner->update(c);
    ++frame;
  }
};

void check_sh(const Sh9Rgb& got, const Sh9Rgb& want, double eps = 1e-5) {
  for (int k = 0; k < kShCount; ++k) {
    for (int ch = 0; ch < 3; ++ch) {
      INFO("coefficient " << k << " channel " << ch);
      CHECK(got.c[k][ch] == Approx(want.c[k][ch]).epsilon(eps).margin(1e-6));
    }
  }
}

// A shipped scenario cut to `seconds` with a cheap reference (its world built by the caller).
Scenario shipped(const std::string& name, double seconds,
                 const std::function<void(nlohmann::json&)>& edit = {}) {
  nlohmann::json doc =
      load_json_file(std::string(AMBISIM_SOURCE_DIR) + "/scenarios/" + name + ".json");
  doc["frames"]["duration_s"] = seconds;
  doc["reference"] = {{"face_size", 8}, {"interval_s", 0.1}};
  if (edit) edit(doc);
  return parse_scenario(doc, name + ".json");
}

const Rgb kSky(0.2f, 0.35f, 0.8f);
const Rgb kSun(6.0f, 5.7f, 5.1f);
const Rgb kGround(0.12f, 0.1f, 0.05f);

}  // namespace

TEST_CASE("relit: the transfer's sky visibility and ground irradiance in closed form",
          "[policies][relit]") {
  const LightingInfo l = light_of(kSky, kSun, 30.0);
  // G = pi A + E sin 30.
  const Rgb g = relit_ground_irradiance(l);
  for (int ch = 0; ch < 3; ++ch)
    CHECK(g[ch] == Approx(std::numbers::pi * kSky[ch] + 0.5 * kSun[ch]));
  // The sun below the horizon gives nothing, whatever its irradiance says.
  LightingInfo night = l;
  night.sun_on = false;
  CHECK(relit_ground_irradiance(night).x == Approx(std::numbers::pi * kSky.x));
  // v: the share of the open sky's upward irradiance the capture sees.
  for (float v : {0.0f, 0.3f, 1.0f}) {
    CHECK(relit_sky_visibility(hemisphere_sh(kSky * v, kGround), l.sky_sh) ==
          Approx(v).margin(1e-6));
  }
  // Brighter than the open sky above (a sunlit wall): clamped to 1; a black sky: 0.
  CHECK(relit_sky_visibility(hemisphere_sh(kSky * 2.0f, kGround), l.sky_sh) == 1.0f);
  CHECK(relit_sky_visibility(hemisphere_sh(kSky, kGround), Sh9Rgb{}) == 0.0f);
}

TEST_CASE("relit answers exactly what it captured while the light does not change",
          "[policies][relit]") {
  const LightingInfo l = light_of(kSky, kSun, 35.0);
  for (const std::vector<std::string>& sets :
       {std::vector<std::string>{}, {"precision=fp16"}, {"order=L1"}}) {
    for (bool static_light : {false, true}) {
      INFO((sets.empty() ? "L2/fp32" : sets[0]) << (static_light ? ", static" : ", changing"));
      Rig rig([&](double) { return l; }, sets, static_light);
      const Sh9Rgb captured = distinct_sh(1.5f);
      const auto req = rig.step({0, 0, 0}, [&](const CaptureRequest&) { return captured; });
      REQUIRE(req.size() == 1);
      CoefficientFormat f;
      f.bands = sets.size() == 1 && sets[0] == "order=L1" ? 2 : 3;
      f.half = sets.size() == 1 && sets[0] == "precision=fp16";
      for (int i = 0; i < 600; ++i) {
        rig.idle({0, 0, 0});
        const LookupResult r = rig.planner->lookup({1.0, 2.0, 0.0});
        REQUIRE(r.sh == f.store(captured));  // bit for bit, every frame
        REQUIRE(r.contributor_count == 1);
        REQUIRE(r.data_time == 0.0);
      }
    }
  }
}

TEST_CASE("relit scales with the sun and the sky: k times the light gives k times the answer",
          "[policies][relit]") {
  // L(t) = L + v (k - 1) S0 + (k - 1) (L - v S0) = k L for any capture and visibility.
  const LightingInfo l0 = light_of(kSky, kSun, 20.0);
  for (const float k : {0.25f, 3.0f, 40.0f}) {
    INFO("k = " << k);
    // The light scales by k from 1 s on.
    for (const Sh9Rgb& captured : {distinct_sh(0.4f), hemisphere_sh(kSky * 0.6f, kGround)}) {
      Rig fresh([&](double t) { return t < 1.0 ? l0 : scaled(l0, k); });
      fresh.step({0, 0, 0}, [&](const CaptureRequest&) { return captured; });
      while (fresh.frame * fresh.dt < 1.5) fresh.idle({0, 0, 0});
      check_sh(fresh.planner->lookup({0, 0, 0}).sh, captured * k);
    }
  }
  // A light that keeps changing: the fade between two probes follows it too. The light is
  // k(t) = 1 + t times l0; probe a (red) at t = 0, probe b (blue) at x = 20 m at t = 1.
  const auto k_of = [](double t) { return static_cast<float>(1.0 + t); };
  Rig rig([&](double t) { return scaled(l0, k_of(t)); }, {"blend_s=0.5"});
  rig.dt = 0.125;
  const Sh9Rgb red = hemisphere_sh(Rgb(0.3f, 0.0f, 0.0f), Rgb(0.1f, 0.0f, 0.0f));
  const Sh9Rgb blue = hemisphere_sh(Rgb(0.0f, 0.0f, 0.3f), Rgb(0.0f, 0.0f, 0.1f));
  rig.step({0, 0, 0}, [&](const CaptureRequest&) { return red; });
  while (rig.frame < 8) rig.idle({0, 0, 0});
  const auto b = rig.step({20, 0, 0}, [&](const CaptureRequest&) { return blue; });  // t = 1
  REQUIRE(b.size() == 1);
  // Frame 9: usable, the fade starts; frame 11 (t = 1.375): halfway. a was captured under
  // k = 1, b under k = 2: both relit to k(1.375).
  rig.idle({20, 0, 0});
  rig.idle({20, 0, 0});
  rig.idle({20, 0, 0});
  const double t = 11 * rig.dt;
  const LookupResult mid = rig.planner->lookup({19, 0, 0});
  REQUIRE(mid.contributor_count == 2);
  CHECK(mid.contributors[0].weight == Approx(0.5f));
  check_sh(mid.sh, sh_lerp(red * k_of(t), blue * (k_of(t) / k_of(1.0)), 0.5f));
  // Points nearest to a: a relit.
  check_sh(rig.planner->lookup({1, 0, 0}).sh, red * k_of(t));
}

TEST_CASE("relit: a change of the sun's colour or height moves the bounce, not the sky term",
          "[policies][relit]") {
  // Capture: sky A at visibility v above, ground B below. Relit: hemisphere_sh(v A', g B) with
  // g = (pi A' + E' sin el') / (pi A + E sin el): upward irradiance pi v A', downward pi g B.
  const float v = 0.7f;
  const Sh9Rgb captured = hemisphere_sh(kSky * v, kGround);
  struct Case {
    const char* what;
    LightingInfo after;
  };
  const Rgb orange(6.0f, 3.2f, 1.1f);
  const Rgb dusk_sky(0.12f, 0.1f, 0.2f);
  for (const Case& c : {Case{"the sun turns orange", light_of(kSky, orange, 30.0)},
                        Case{"the sun sinks from 30 to 8 deg", light_of(kSky, kSun, 8.0)},
                        Case{"the sun sets", light_of(kSky, kSun, -2.0)},
                        Case{"the sky turns dusky", light_of(dusk_sky, kSun, 30.0)}}) {
    INFO(c.what);
    const LightingInfo before = light_of(kSky, kSun, 30.0);
    Rig rig([&](double t) { return t < 1.0 ? before : c.after; });
    rig.step({0, 0, 0}, [&](const CaptureRequest&) { return captured; });
    while (rig.frame * rig.dt < 1.5) rig.idle({0, 0, 0});
    const Sh9Rgb got = rig.planner->lookup({0, 0, 0}).sh;

    const Rgb g0 = relit_ground_irradiance(before), g1 = relit_ground_irradiance(c.after);
    const Rgb sky1 =
        c.after.sky_sh.c[0] / static_cast<float>(2.0 * std::numbers::pi * kShY00);  // A'
    const Rgb g = g1 / g0;
    check_sh(got, hemisphere_sh(sky1 * v, kGround * g));
    const Rgb up = sh_irradiance(got, {0, 0, 1}), down = sh_irradiance(got, {0, 0, -1});
    for (int ch = 0; ch < 3; ++ch) {
      CHECK(up[ch] == Approx(std::numbers::pi * v * sky1[ch]).epsilon(1e-5));
      CHECK(down[ch] == Approx(std::numbers::pi * kGround[ch] * g[ch]).epsilon(1e-5));
    }
  }
  // The orange sun in numbers: the bounce's red keeps its share, its blue loses 4/5 of the sun.
  const Rgb g = relit_ground_irradiance(light_of(kSky, orange, 30.0)) /
                relit_ground_irradiance(light_of(kSky, kSun, 30.0));
  CHECK(g.x == Approx(1.0));
  CHECK(g.z == Approx((std::numbers::pi * 0.8 + 0.55) / (std::numbers::pi * 0.8 + 2.55)));
}

TEST_CASE("relit never recaptures a probe for lighting", "[policies][relit][heavy]") {
  // A day in 200 s (the sun from -10 to 60 deg and back, the sky with it) against a light that
  // never changes: a hovering camera captures once, a camera pacing 40 m back and forth captures
  // its stretch once, and both count the same captures in both lights.
  const auto day = [](double t) {
    const double el = -10.0 + 70.0 * std::sin(std::numbers::pi * t / 200.0);
    const float k = static_cast<float>(std::max(0.02, std::sin(std::max(el, 1.0) * kDeg)));
    return light_of(kSky * k, kSun, el);
  };
  const LightingInfo noon = light_of(kSky, kSun, 40.0);
  for (bool pacing : {false, true}) {
    std::int64_t counts[2] = {0, 0};
    for (int changing = 0; changing < 2; ++changing) {
      Rig rig(changing ? std::function<LightingInfo(double)>(day) : [&](double) { return noon; });
      for (int i = 0; i < 12000; ++i) {
        const double x = pacing ? 20.0 - 20.0 * std::cos(2.0 * std::numbers::pi * i / 1200.0) : 0.0;
        counts[changing] += static_cast<std::int64_t>(
            rig.step({x, 0, 0}, [&](const CaptureRequest&) { return distinct_sh(1.0f); }).size());
      }
      CHECK(rig.planner->stats().live_probes == counts[changing]);
    }
    INFO((pacing ? "pacing" : "hovering"));
    CHECK(counts[0] == counts[1]);
    CHECK(counts[0] == (pacing ? 5 : 1));  // at 0, 8.x, 16.x, 24.x, 32.x m
  }

  // The simulator: day_cycle (the sun rising at 360x) against the same flight under a fixed
  // sun: the same captures, at the same places.
  const Scenario changing = shipped("day_cycle", 50);
  const Scenario fixed = shipped("day_cycle", 50, [](nlohmann::json& d) {
    d["world"]["sun"] = {{"elevation_deg", 30}, {"azimuth_deg", 120}};
  });
  REQUIRE_FALSE(changing.world.lighting().is_static());
  REQUIRE(fixed.world.lighting().is_static());
  std::vector<ProbeNodeView> nodes[2];
  std::int64_t captures[2] = {0, 0};
  for (int i = 0; i < 2; ++i) {
    const World world(i == 0 ? changing.world : fixed.world);
    auto p = make_planner("relit");
    captures[i] = simulate_without_reference(i == 0 ? changing : fixed, world, *p).captures_started;
    p->describe_nodes(nodes[i]);
  }
  CHECK(captures[0] == captures[1]);
  CHECK(captures[0] >= 9);  // walking at 1.5 m/s for 50 s: the first, then one per 8 m
  CHECK(captures[0] <= 11);
  REQUIRE(nodes[0].size() == nodes[1].size());
  for (std::size_t i = 0; i < nodes[0].size(); ++i) CHECK(nodes[0][i].centre == nodes[1][i].centre);
}

TEST_CASE("relit equals nearest wherever the world's global light does not change",
          "[policies][relit][heavy]") {
  // The static motorway; cloud_shadows, whose sun and mean sky stay (only the clouds' shadows
  // move); fog_bank, whose fog thickens under a fixed sun: relit sees neither the shadows nor
  // the fog, so relighting changes nothing, and every error, pop and coverage figure is
  // nearest's (whose 60 s lifetime outlasts these runs).
  for (const char* name : {"motorway", "cloud_shadows", "fog_bank"}) {
    INFO(name);
    const Scenario sc = shipped(name, 6);
    const World world(sc.world);
    const auto reference = compute_reference_track(sc, world);
    auto relit = make_planner("relit");
    auto nearest = make_planner("nearest");
    const RunResult rr = simulate(sc, world, *reference, *relit);
    const RunResult rn = simulate(sc, world, *reference, *nearest);
    auto jr = RunMetrics::to_json(rr.summary);
    auto jn = RunMetrics::to_json(rn.summary);
    CHECK(jr["memory"] != jn["memory"]);  // each counts its own layout
    jr.erase("memory");
    jn.erase("memory");
    CHECK(jr.dump() == jn.dump());
    CHECK(rr.captures_started == rn.captures_started);
  }
}

TEST_CASE("relit follows a sunrise that nearest does not", "[policies][relit]") {
  // day_cycle from 02:58 (360x: the sun rises at 03:04, 1 s in, and climbs for 71 minutes):
  // walking at 1.5 m/s the camera captures every 5.3 s, 32 minutes of the day apart, so
  // nearest shows each probe's moment of the dawn for 5 s while the light grows several times.
  const Scenario sc = shipped(
      "day_cycle", 12, [](nlohmann::json& d) { d["world"]["sun"]["path"]["start"] = "02:58"; });
  const World world(sc.world);
  const auto reference = compute_reference_track(sc, world);
  auto relit = make_planner("relit");
  auto nearest = make_planner("nearest");
  const Summary r = simulate(sc, world, *reference, *relit).summary;
  const Summary n = simulate(sc, world, *reference, *nearest).summary;
  // Measured: relit dE00 mean 1.64, p95 2.75; nearest 14.6 and 33.1.
  CHECK(r.de2000.mean < 0.25 * n.de2000.mean);
  CHECK(r.de2000.p95 < 0.25 * n.de2000.p95);
}

TEST_CASE("relit honours the planner contract under the shipped changing light",
          "[policies][relit]") {
  // The contract test's worlds are shared by seed (see shipped()), so here the four scenarios of
  // changing light run in their own worlds, each at a stretch where its light moves: the
  // sunset with the lamps switching on, the sunrise, the cloud shadows, the fog rising.
  struct Stretch {
    const char* name;
    std::function<void(nlohmann::json&)> edit;
  };
  const std::vector<Stretch> stretches = {
      {"sunset_drive",
       [](nlohmann::json& d) {
         d["world"]["sun"]["path"]["keys"] = {
             {{"time_s", 0}, {"elevation_deg", 3}, {"azimuth_deg", 285}},
             {{"time_s", 4}, {"elevation_deg", -2}, {"azimuth_deg", 290}}};
       }},
      {"day_cycle", [](nlohmann::json& d) { d["world"]["sun"]["path"]["start"] = "02:55"; }},
      {"cloud_shadows", {}},
      {"fog_bank",
       [](nlohmann::json& d) {
         d["world"]["fog"]["height"]["keys"] = {
             {{"time_s", 0}, {"density_per_m", 0.0}, {"base_m", 25}},
             {{"time_s", 4}, {"density_per_m", 0.04}, {"base_m", 45}}};
       }},
  };
  for (const auto& st : stretches) {
    INFO(st.name);
    const Scenario sc = shipped(st.name, 4, st.edit);
    REQUIRE_FALSE(sc.world.lighting().is_static());
    const World world(sc.world);
    const auto reference = compute_reference_track(sc, world);
    auto planner = make_planner("relit");
    const RunResult r = simulate(sc, world, *reference, *planner);
    CHECK(r.summary.frames == static_cast<std::int64_t>(reference->frames.size()));
    CHECK(r.summary.faces.granted <=
          static_cast<std::int64_t>(std::ceil(sc.budget.faces_per_frame * r.summary.frames)));
    CHECK(r.captures_started >= 1);
    CHECK(std::isfinite(r.summary.de2000.mean));
    CHECK(r.summary.memory.max_bytes < (std::int64_t{64} << 20));
    for (const glm::dvec3& p : {glm::dvec3(-1e5, 3e4, 50.0), glm::dvec3(2000, 2000, -500),
                                glm::dvec3(1e6, 1e6, 1e4), glm::dvec3(0.0)}) {
      const Sh9Rgb sh = planner->lookup(p).sh;
      for (const auto& c : sh.c)
        CHECK((std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z)));
    }
    auto again = make_planner("relit");
    const RunResult r2 = simulate(sc, world, *reference, *again);
    CHECK(result_json(sc, {"relit", {}}, r).dump() == result_json(sc, {"relit", {}}, r2).dump());
  }
}

TEST_CASE("relit's memory counts what it keeps per probe", "[policies][relit]") {
  const LightingInfo l = light_of(kSky, kSun, 30.0);
  for (bool static_light : {false, true}) {
    Rig rig([&](double) { return l; }, {"blend_s=0"}, static_light);
    rig.step({0, 0, 0}, [&](const CaptureRequest&) { return distinct_sh(1.0f); });
    const std::int64_t one = rig.planner->stats().bytes;
    rig.step({20, 0, 0}, [&](const CaptureRequest&) { return distinct_sh(2.0f); });
    const std::int64_t two = rig.planner->stats().bytes;
    // Relit: the capture, the sky it was taken under and the relit set (3 x 108 bytes at
    // L2/fp32); under static light the capture alone.
    const std::int64_t sets = static_light ? 1 : 3;
    CHECK(two - one >= sets * 108);
    CHECK(two - one < sets * 108 + 128);
  }
  // Before any probe: the default ambient.
  auto p = make_planner("relit");
  CHECK(p->lookup({0, 0, 0}).fell_back);
  CHECK(p->lookup({0, 0, 0}).sh == default_ambient_sh());
}
