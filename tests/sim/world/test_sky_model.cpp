// The Preetham sky, the sun through the atmosphere and twilight against the model's own values
// (tables computed from the paper's formulas and coefficients, cross-checked against Smits',
// Mitsuba's and Bruneton's implementations) and against physical checks.
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "sim/world/sky_model.h"

using namespace ambisim;

namespace {

constexpr double kTableTol = 1.5e-3;  // kcd/m^2: the tables carry 3 decimals

glm::dvec3 dir(double zenith_deg, double azimuth_deg) {
  const double z = zenith_deg * std::numbers::pi / 180.0,
               a = azimuth_deg * std::numbers::pi / 180.0;
  return {std::sin(z) * std::cos(a), std::sin(z) * std::sin(a), std::cos(z)};
}

double lum(const Rgb& c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

}  // namespace

TEST_CASE("Preetham: zenith luminance by turbidity and sun zenith", "[world][sky]") {
  struct Row {
    double t, theta_deg, yz;
  };
  const Row rows[] = {{2, 0, 15.501}, {3, 0, 29.477},  {6, 0, 57.180},  {10, 0, 76.356},
                      {2, 30, 5.887}, {3, 30, 10.413}, {6, 30, 22.067}, {3, 60, 5.139},
                      {3, 80, 2.829}, {3, 90, 1.773},  {10, 90, 0.264}, {8, 75, 6.185}};
  for (const Row& r : rows) {
    CAPTURE(r.t, r.theta_deg);
    CHECK(PreethamSky::zenith_luminance(r.t, r.theta_deg * std::numbers::pi / 180.0) ==
          Approx(r.yz).margin(kTableTol));
  }
}

TEST_CASE("Preetham: zenith chromaticity and the Perez coefficients", "[world][sky]") {
  struct Row {
    double t, theta_deg, x, y;
  };
  const Row rows[] = {{2, 0, 0.26674, 0.27720},
                      {3, 30, 0.25343, 0.25979},
                      {3, 90, 0.28373, 0.30531},
                      {6, 60, 0.26547, 0.28179},
                      {10, 30, 0.28458, 0.30828}};
  for (const Row& r : rows) {
    CAPTURE(r.t, r.theta_deg);
    const double th = r.theta_deg * std::numbers::pi / 180.0;
    CHECK(PreethamSky::zenith_chromaticity(r.t, th, 1) == Approx(r.x).margin(1e-5));
    CHECK(PreethamSky::zenith_chromaticity(r.t, th, 2) == Approx(r.y).margin(1e-5));
  }
  double c[5];
  PreethamSky::perez_coefficients(3.0, 0, c);  // Y at T = 3
  CHECK(c[0] == Approx(-0.9269).margin(1e-9));
  CHECK(c[1] == Approx(-0.6387).margin(1e-9));
  CHECK(c[2] == Approx(5.2570).margin(1e-9));
  CHECK(c[3] == Approx(-2.2153).margin(1e-9));
  CHECK(c[4] == Approx(0.1693).margin(1e-9));
}

TEST_CASE("Preetham: sky samples in linear sRGB", "[world][sky]") {
  // T = 3, sun at zenith angle 30 deg (azimuth 0): samples of the model in cd/m^2.
  const PreethamSky sky(3.0, dir(30, 0));
  const Rgb zenith = sky.radiance({0, 0, 1});
  CHECK(zenith.x == Approx(7.184).epsilon(1e-3));
  CHECK(zenith.y == Approx(10.500).epsilon(1e-3));
  CHECK(zenith.z == Approx(19.068).epsilon(1e-3));
  // 45 deg up, opposite the sun: Y 5967.8 cd/m^2, x 0.2394, y 0.2514.
  const glm::dvec3 opp = sky.xyY(dir(45, 180));
  CHECK(opp.z == Approx(5.9678).epsilon(1e-3));
  CHECK(opp.x == Approx(0.2394).margin(2e-4));
  CHECK(opp.y == Approx(0.2514).margin(2e-4));
  // The horizon toward the sun: Y 11456.7, x 0.3217 (yellower than the zenith).
  const glm::dvec3 hor = sky.xyY(dir(89.94, 0));
  CHECK(hor.z == Approx(11.4567).epsilon(2e-3));
  CHECK(hor.x == Approx(0.3217).margin(2e-4));
}

TEST_CASE("Preetham: physical checks", "[world][sky]") {
  // Zenith luminance falls as the sun sets, at every turbidity of the model's range.
  for (double t : {2.0, 3.0, 5.0, 8.0, 10.0}) {
    double last = 1e9;
    for (double th = 0.0; th <= 90.0; th += 1.0) {
      const double y = PreethamSky::zenith_luminance(t, th * std::numbers::pi / 180.0);
      CAPTURE(t, th);
      CHECK(y < last);
      last = y;
    }
  }
  // Brighter toward the sun: 10 deg from the sun beats the zenith beats the anti-solar sky at
  // the same height.
  const PreethamSky sky(3.0, dir(60, 90));
  const double near_sun = lum(sky.radiance(dir(60, 80)));
  const double zenith = lum(sky.radiance({0, 0, 1}));
  const double away = lum(sky.radiance(dir(60, 270)));
  CHECK(near_sun > zenith);
  CHECK(near_sun > away);
  // The zenith is blue, the horizon toward a low sun warm.
  const PreethamSky low(3.0, dir(80, 0));
  const Rgb z = low.radiance({0, 0, 1}), h = low.radiance(dir(89.9, 0));
  CHECK(z.z > z.y);
  CHECK(z.y > z.x);
  CHECK(h.x > h.z);
}

TEST_CASE("the sun through the atmosphere: dimmer and redder toward the horizon", "[world][sky]") {
  // T = 3, sun at the zenith: the green channel's transmittance is exp(-0.3309) = 0.718 over
  // air mass 0.9997 (Kasten-Young at 0 deg).
  const Rgb e0 = sun_irradiance(90.0, 3.0);
  const double exo_g = xyY_to_linear_srgb(0.317, 0.326, 1.0).y * 126.956;
  CHECK(e0.y == Approx(exo_g * std::exp(-0.999712 * 0.3309)).epsilon(2e-3));
  // Normal illuminance of the order of 90 klx at noon (Preetham's spectral sun: 91.4 klx).
  CHECK(lum(e0) == Approx(91.4).epsilon(0.05));
  double last_lum = 1e9, last_rg = 0.0, last_bg = 1e9;
  for (double el : {90.0, 60.0, 30.0, 10.0, 5.0, 2.0}) {
    const Rgb e = sun_irradiance(el, 3.0);
    CAPTURE(el);
    CHECK(lum(e) < last_lum);
    CHECK(e.x / e.y > last_rg);
    CHECK(e.z / e.y < last_bg);
    last_lum = lum(e);
    last_rg = e.x / e.y;
    last_bg = e.z / e.y;
  }
  CHECK(sun_irradiance(0.0, 3.0) == Rgb(0.0f));
  CHECK(sun_irradiance(-3.0, 3.0) == Rgb(0.0f));
}

TEST_CASE("twilight: USNO Circular 171's illuminance, continuous at sunset", "[world][sky]") {
  // The formula's published check values (the skylight package's tests): 123786 lux at 90 deg.
  CHECK(usno_global_illuminance_lux(90.0) == Approx(123786).epsilon(1e-4));
  // End of civil twilight, -6 deg: 2.99 lux, inside the AMS glossary's 3.5-2 lux.
  const double civil = usno_global_illuminance_lux(-6.0);
  CHECK(civil == Approx(2.99).margin(0.01));
  CHECK(civil > 2.0);
  CHECK(civil < 3.5);
  CHECK(twilight_factor(0.0) == 1.0);
  CHECK(twilight_factor(-0.01) == Approx(1.0).margin(0.01));
  // Falling until the night floor (reached near -13.5 deg, where the formula drops below
  // starlight), constant below it.
  const double floor = 0.002 / usno_global_illuminance_lux(0.0);
  double last = 1.0;
  for (double el = -0.5; el >= -18.0; el -= 0.5) {
    CAPTURE(el);
    const double f = twilight_factor(el);
    if (last > floor) {
      CHECK(f < last);
    } else {
      CHECK(f == last);
    }
    last = f;
  }
  // Floored at the night sky: 0.002 lux against 757 lux at sunset.
  CHECK(twilight_factor(-40.0) == Approx(0.002 / usno_global_illuminance_lux(0.0)).epsilon(1e-9));
}
