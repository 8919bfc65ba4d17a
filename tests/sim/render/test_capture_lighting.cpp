// Captures in the light of a moment: the lamp layer adds up, the sun moves the shadows, the
// model's static and legacy cases, and what planners are told.
#include <catch2/catch.hpp>
#include <cmath>

#include "sim/render/capture.h"
#include "sim/world/illumination.h"
#include "sim/world/lighting_model.h"
#include "sim/world/world.h"

using namespace ambisim;

namespace {

// A 512 m world with its road, lamps and a solar sunset at 57.7 N.
WorldParams dusk_world() {
  WorldParams p;
  p.seed = 3;
  p.size_m = {512.0, 512.0};
  p.sky.model = SkyParams::Model::preetham;
  p.sun.path.type = SunPathParams::Type::solar;
  p.sun.path.year = 2026;
  p.sun.path.month = 9;
  p.sun.path.day = 20;
  p.sun.path.latitude_deg = 57.7;
  p.sun.path.longitude_deg = 12.0;
  p.sun.path.utc_offset_h = 1.0;
  p.sun.path.start_s = 17.0 * 3600.0;  // elevation 9.5 deg; sunset (CET) about 18:15
  p.sun.path.time_scale = 60.0;        // an hour a minute
  p.lamps.enabled = true;
  return p;
}

}  // namespace

TEST_CASE("the lamp layer adds up: all = base + level x lamps", "[capture][lighting]") {
  const World w(dusk_world());
  LightingModel model(w);
  const LightingState& s = model.state_at(80.0);  // 18:20 local: dusk
  REQUIRE(s.lamps != nullptr);
  LightingState on = s;
  on.lamp_level = 1.0;
  const glm::dvec3 p = w.road().at(200.0) + glm::dvec3(0.0, 0.0, 1.5);
  const CubeMap all = capture(Illumination(w, on, LightLayer::all), p, 8);
  const CubeMap base = capture(Illumination(w, on, LightLayer::base), p, 8);
  const CubeMap lamps = capture(Illumination(w, on, LightLayer::lamps), p, 8);
  double lamp_energy = 0.0;
  for (std::size_t k = 0; k < all.texel.size(); ++k) {
    const Rgb sum = base.texel[k] + lamps.texel[k];
    CHECK(all.texel[k].y == Approx(sum.y).epsilon(1e-5).margin(1e-9));
    lamp_energy += lamps.texel[k].y;
  }
  CHECK(lamp_energy > 0.0);  // the road under the lamps is lit by them
  // Off, the lamps add nothing.
  LightingState off = s;
  off.lamp_level = 0.0;
  const CubeMap dark = capture(Illumination(w, off, LightLayer::all), p, 8);
  for (std::size_t k = 0; k < dark.texel.size(); ++k) {
    CHECK(dark.texel[k].y == Approx(base.texel[k].y).epsilon(1e-6).margin(1e-12));
  }
}

TEST_CASE("a solar path: the sun sets, the lamps switch on, the light falls", "[lighting]") {
  const World w(dusk_world());
  LightingModel model(w);
  CHECK_FALSE(model.is_static());
  double el0 = 0.0, el1 = 0.0;
  model.sun_at(0.0, &el0);
  model.sun_at(90.0, &el1);                 // 18:30
  CHECK(el0 == Approx(9.52).margin(0.01));  // NOAA's elevation at 17:00 CET
  CHECK(el1 < 0.0);
  const LightingInfo day = model.info_at(0.0), night = model.info_at(90.0);
  CHECK(day.sun_on);
  CHECK_FALSE(night.sun_on);
  CHECK(day.lamp_level == 0.0);
  CHECK(night.lamp_level == 1.0);
  CHECK(day.sky_sh.c[0].y > 10.0f * night.sky_sh.c[0].y);
  // The rate is at least the sun's angular speed: 60 x 15 deg per hour = 0.0044 rad/s.
  const glm::dvec3 a = model.sun_at(0.0).dir, b = model.sun_at(1.0).dir;
  const double omega = std::acos(a.x * b.x + a.y * b.y + a.z * b.z);
  CHECK(omega == Approx(0.0044).margin(0.0008));
  CHECK(day.change_rate >= omega * 0.99);
}

TEST_CASE("static and legacy lighting", "[lighting]") {
  WorldParams legacy;
  legacy.seed = 3;
  legacy.size_m = {256.0, 256.0};
  legacy.sky.model = SkyParams::Model::gradient;
  CHECK(legacy.lighting().is_legacy());
  CHECK(legacy.lighting().is_static());
  WorldParams clouds = legacy;
  clouds.clouds.enabled = true;
  CHECK_FALSE(clouds.lighting().is_static());
  CHECK_FALSE(clouds.lighting().is_legacy());
  WorldParams sky = legacy;
  sky.sky.model = SkyParams::Model::preetham;
  CHECK(sky.lighting().is_static());
  CHECK_FALSE(sky.lighting().is_legacy());
  // A legacy world renders exactly as before: the precomputed radiance.
  const World w(legacy);
  LightingModel m(w);
  const glm::dvec3 p(128.0, 128.0, w.surface_height(128.0, 128.0) + 2.0);
  const CubeMap a = capture(w, p, 8);
  const CubeMap b = capture(Illumination(w, m.state_at(12.0)), p, 8);
  CHECK(a.texel == b.texel);
}
