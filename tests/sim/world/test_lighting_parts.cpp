// The parts of the lighting that changes: the cloud layer, street lamps, height fog, the
// moving sun's shadows (against exact maps), and the model's time behaviour.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <numbers>

#include <glm/geometric.hpp>

#include "sim/world/cloud_layer.h"
#include "sim/world/height_fog.h"
#include "sim/world/illumination.h"
#include "sim/world/lighting_model.h"
#include "sim/world/shadow_heights.h"
#include "sim/world/spline.h"
#include "sim/world/street_lamps.h"
#include "sim/world/sun_shadows.h"
#include "sim/world/world.h"

using namespace ambisim;

TEST_CASE("clouds: the cover fraction asked for, drifting with the wind", "[world][clouds]") {
  for (double coverage : {0.2, 0.4, 0.7}) {
    CloudParams p;
    p.enabled = true;
    p.coverage = coverage;
    p.softness = 0.02;  // nearly hard edges: the mean cover is the covered share
    const CloudLayer c(p, 1500.0);
    CAPTURE(coverage);
    CHECK(c.mean_cover() == Approx(coverage).margin(0.02));
  }
  CloudParams p;
  p.enabled = true;
  p.wind_mps = 12.0;
  p.wind_from_deg = 270.0;  // from the west: the field moves toward +x
  const CloudLayer c(p, 1500.0);
  CHECK(c.wind().x == Approx(12.0).margin(1e-9));
  CHECK(c.wind().y == Approx(0.0).margin(1e-9));
  // The field is carried: what is at x at time 0 is at x + 12 t at time t.
  for (double x : {0.0, 333.3, 1234.5}) {
    CHECK(c.cover(x + 12.0 * 10.0, 77.0, 10.0) == Approx(c.cover(x, 77.0, 0.0)).margin(1e-9));
  }
  // The tile repeats seamlessly every 8 x scale_m.
  const double tile = 8.0 * p.scale_m;
  CHECK(c.cover(123.0 + tile, 456.0, 0.0) == Approx(c.cover(123.0, 456.0, 0.0)).margin(1e-9));
  // The sun's transmittance: between 1 - opacity and 1; 1 above the layer.
  const glm::dvec3 sun = glm::normalize(glm::dvec3(0.3, 0.2, 0.9));
  double lo = 1.0, hi = 0.0;
  for (int k = 0; k < 200; ++k) {
    const double t = c.sun_transmittance({17.0 * k, 11.0 * k, 50.0}, sun, 0.0);
    lo = std::min(lo, t);
    hi = std::max(hi, t);
  }
  CHECK(lo >= 1.0 - p.opacity - 1e-12);
  CHECK(hi <= 1.0 + 1e-12);
  CHECK(lo < hi);  // there are clouds and gaps
  CHECK(c.sun_transmittance({0, 0, 2000.0}, sun, 0.0) == 1.0);
}

TEST_CASE("street lamps: inverse square under a cone, switched by the sun or a schedule",
          "[world][lamps]") {
  // A straight road along +x at z = 0; lamps every 100 m, 10 m high, 4 m off the centre.
  const Spline3 road({{0, 0, 0}, {1000, 0, 0}});
  LampParams p;
  p.enabled = true;
  p.spacing_m = 100.0;
  p.height_m = 10.0;
  p.offset_m = 4.0;
  p.colour = {1.0f, 1.0f, 1.0f};
  p.intensity_kcd = 2.0;
  p.cone_deg = 60.0;
  const StreetLamps lamps(p, road, 12.0);
  REQUIRE(lamps.positions().size() == 20);
  const glm::dvec3 l = lamps.positions()[0];
  CHECK(l.x == Approx(50.0));
  CHECK(std::abs(l.y) == Approx(4.0));
  CHECK(l.z == Approx(10.0));
  // Right below a lamp: I / h^2 from it, plus I h / d^3 from its partner across the road (8 m
  // off, 38.7 deg from its axis: inside the full-power cone of 50 deg).
  const glm::dvec3 up(0, 0, 1);
  const auto flat = [](double off) {
    const double d = std::hypot(off, 10.0);
    return 2.0 * 10.0 / (d * d * d);  // I cos / d^2 with cos = h / d
  };
  CHECK(lamps.irradiance({l.x, l.y, 0.0}, up).y == Approx(2.0 / 100.0 + flat(8.0)).epsilon(1e-6));
  // 5 m along the road from it: both lamps of the pair, 5 and sqrt(25 + 64) m off.
  CHECK(lamps.irradiance({l.x + 5.0, l.y, 0.0}, up).y ==
        Approx(flat(5.0) + flat(std::hypot(5.0, 8.0))).epsilon(1e-6));
  // Outside the 60 deg cone (tan 60 x 10 m = 17.3 m off): nothing from this lamp (the next
  // lamps are 100 m away).
  CHECK(lamps.irradiance({l.x + 20.0, l.y, 0.0}, up).y == 0.0f);
  // A surface facing away gets nothing.
  CHECK(lamps.irradiance({l.x, l.y, 0.0}, {0, 0, -1}).y == 0.0f);
  // Photocell: on below 2 deg of sun elevation.
  CHECK(lamps.level(0.0, 10.0) == 0.0);
  CHECK(lamps.level(0.0, 1.0) == 1.0);
  LampParams q = p;
  q.schedule = {{5.0, true}, {8.0, false}};
  const StreetLamps timed(q, road, 12.0);
  CHECK(timed.level(4.9, -30.0) == 0.0);
  CHECK(timed.level(5.0, 60.0) == 1.0);
  CHECK(timed.level(8.0, -30.0) == 0.0);
}

TEST_CASE("height fog: the closed-form optical depth against numerical integration",
          "[world][fog]") {
  FogState f;
  f.height = true;
  f.density_per_m = 0.02;
  f.base_m = 30.0;
  f.falloff_m = 12.0;
  f.homogeneous_per_m = 0.001;
  const auto numeric = [&](const glm::dvec3& o, const glm::dvec3& d, double t) {
    constexpr int kSteps = 200000;
    double sum = 0.0;
    for (int k = 0; k < kSteps; ++k) sum += f.sigma_at((o + d * ((k + 0.5) * t / kSteps)).z);
    return sum * t / kSteps;
  };
  const glm::dvec3 o(0, 0, 40.0);
  for (const glm::dvec3& d :
       {glm::dvec3(0, 0, 1), glm::dvec3(0, 0, -1), glm::normalize(glm::dvec3(1, 0, 0.2)),
        glm::normalize(glm::dvec3(1, 0, -0.05)), glm::dvec3(1, 0, 0)}) {
    CAPTURE(d.x, d.z);
    CHECK(f.optical_depth(o, d, 300.0) == Approx(numeric(o, d, 300.0)).epsilon(1e-6));
  }
  // Escaping upward: density falloff e^{-(o.z - base)/falloff} / d.z (no homogeneous part).
  const double up = f.optical_depth(o, {0, 0, 1}, std::numeric_limits<double>::infinity());
  CHECK(up == Approx(0.02 * 12.0 * std::exp(-10.0 / 12.0)).epsilon(1e-12));
  // Keys: density and base linear in time.
  FogParams p;
  p.height_enabled = true;
  p.height_keys = {{0.0, 0.0, 30.0}, {60.0, 0.03, 60.0}};
  const FogState mid = fog_at(p, 30.0);
  CHECK(mid.density_per_m == Approx(0.015));
  CHECK(mid.base_m == Approx(45.0));
  CHECK(fog_at(p, 100.0).base_m == Approx(60.0));
}

TEST_CASE("a moving sun's shadows: interpolated key maps against the exact map",
          "[world][shadows]") {
  // A 1 km world; the sun sinks from 30 to 6 deg over 120 s while swinging 30 deg in azimuth.
  WorldParams wp;
  wp.seed = 2;
  wp.size_m = {1024.0, 1024.0};
  wp.sky.model = SkyParams::Model::gradient;
  const World w(wp);
  const auto sun_at = [](double t) {
    SunShadows::Sun s;
    const double el = (30.0 - 24.0 * t / 120.0) * std::numbers::pi / 180.0;
    const double az = (200.0 + 30.0 * t / 120.0) * std::numbers::pi / 180.0;
    s.dir = {std::sin(az) * std::cos(el), std::cos(az) * std::cos(el), std::sin(el)};
    s.on = true;
    return s;
  };
  SunShadows shadows(w, sun_at, 1.0);
  std::size_t cells = 0, wrong = 0;
  for (double t = 0.0; t <= 120.0; t += 7.3) {
    shadows.set_time(t);
    const std::vector<float> exact = shadows.exact_map(t);
    for (int j = 0; j < w.ny(); j += 2) {
      for (int i = 0; i < w.nx(); i += 2) {
        const std::size_t k = w.cell_index(i, j);
        const float top = w.column_top(i, j);
        ++cells;
        if ((top >= exact[k]) != (top >= shadows.height(k))) ++wrong;
      }
    }
  }
  // Keys at most 1 deg of sun travel apart: about 30 for 24 + 30 deg of path.
  CHECK(shadows.keys().size() >= 20);
  CHECK(shadows.keys().size() <= 45);
  // The stated error of the shortcut (docs: scenarios/README.md): under 0.5 % of the column
  // tops lit where they are shadowed or the reverse.
  const double share = static_cast<double>(wrong) / static_cast<double>(cells);
  CAPTURE(share);
  CHECK(share < 0.005);
  // In time order each key map is computed once.
  CHECK(shadows.maps_computed() <= shadows.keys().size() + 1);
}
