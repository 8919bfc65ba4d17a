// SPEC section 2 oracles for SH irradiance: constant radiance, sky over ground, and the L2
// ringing of a directional light.
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "sim/sh/sh_projection.h"
#include "test_sh_support.h"

using namespace ambisim;

namespace {

// Constant radiance: E / (pi L) - 1, measured 1.0e-7 (fast, float tables) and 5.1e-8
// (naive) over 26 normals at N = 16; the same for the thesis' uniform weights.
constexpr double kConstantRelTol = 1e-6;
// Sky A / ground B with even N (the horizon falls on texel edges, so radiance is assigned
// exactly): |E - closed form| / pi, the texel-centre quadrature error of Y_10, measured
// 5.78e-4 at N = 16 and 3.61e-5 at N = 64 (exact weights); 1.44e-2 and 1.41e-2 with the
// uniform thesis weights.
constexpr double kSkyGroundTol16 = 7e-4;
constexpr double kSkyGroundTol64 = 5e-5;
// Directional light given directly as coefficients: only float rounding, measured < 1e-7.
constexpr double kDirectionalTol = 1e-6;

Rgb sky_ground_closed_form(const Rgb& sky, const Rgb& ground, double cos_theta) {
  return Rgb(std::numbers::pi * (glm::dvec3(sky) * (1.0 + cos_theta) / 2.0 +
                                 glm::dvec3(ground) * (1.0 - cos_theta) / 2.0));
}

// L2 approximation of the irradiance of a unit directional light, normalised so that the
// exact irradiance facing it is 1: f(t) = 1/4 + t/2 + 5/16 (3 t^2 - 1) / 2, t = n . d.
double directional_l2(double t) { return 0.25 + 0.5 * t + 5.0 / 16.0 * (3.0 * t * t - 1.0) / 2.0; }

}  // namespace

TEST_CASE("constant radiance gives E = pi L for every normal", "[sh][irradiance]") {
  const Rgb l(0.3f, 1.0f, 2.5f);
  const CubeMap cube = test::cube_from(16, [&](const glm::dvec3&) { return l; });
  for (auto weighting : {TexelWeighting::exact_solid_angle, TexelWeighting::uniform_thesis}) {
    const Sh9Rgb fast = projector_for(16, weighting).project(cube);
    const Sh9Rgb naive = project_cube_naive(cube, weighting);
    for (const glm::dvec3& n : test::normals26()) {
      for (const Sh9Rgb* sh : {&fast, &naive}) {
        const Rgb e = sh_irradiance(*sh, n);
        for (int ch = 0; ch < 3; ++ch) {
          CHECK(std::abs(e[ch] / (std::numbers::pi * l[ch]) - 1.0) < kConstantRelTol);
        }
      }
    }
  }
}

TEST_CASE("sky above ground below gives the closed-form irradiance", "[sh][irradiance]") {
  const Rgb sky(0.2f, 0.5f, 1.0f), ground(0.4f, 0.3f, 0.1f);
  double max_err_exact16 = 0.0, max_err_uniform16 = 0.0;
  for (int n : {16, 64}) {
    const CubeMap cube =
        test::cube_from(n, [&](const glm::dvec3& d) { return d.z > 0.0 ? sky : ground; });
    const Sh9Rgb fast = projector_for(n).project(cube);
    const Sh9Rgb naive = project_cube_naive(cube);
    const Sh9Rgb uniform = projector_for(n, TexelWeighting::uniform_thesis).project(cube);
    const double tol = n == 16 ? kSkyGroundTol16 : kSkyGroundTol64;
    for (int a = 0; a < 8; ++a) {
      const double phi = 2.0 * std::numbers::pi * a / 8.0 + 0.1;
      for (int k = 0; k <= 36; ++k) {
        const double theta = std::numbers::pi * k / 36.0;
        const glm::dvec3 normal(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                                std::cos(theta));
        const Rgb want = sky_ground_closed_form(sky, ground, std::cos(theta));
        const Rgb e_fast = sh_irradiance(fast, normal), e_naive = sh_irradiance(naive, normal);
        const Rgb e_uniform = sh_irradiance(uniform, normal);
        for (int ch = 0; ch < 3; ++ch) {
          INFO("N = " << n << " theta " << theta << " phi " << phi);
          CHECK(std::abs(e_fast[ch] - want[ch]) / std::numbers::pi < tol);
          CHECK(std::abs(e_naive[ch] - want[ch]) / std::numbers::pi < tol);
          if (n == 16) {
            max_err_exact16 =
                std::max(max_err_exact16, std::abs(e_naive[ch] - want[ch]) / std::numbers::pi);
            max_err_uniform16 =
                std::max(max_err_uniform16, std::abs(e_uniform[ch] - want[ch]) / std::numbers::pi);
          }
        }
      }
    }
  }
  // The uniform thesis weight is off by 1.44e-2, 25x the exact-weight error (measured).
  CHECK(max_err_uniform16 > 10.0 * max_err_exact16);
  CHECK(max_err_uniform16 > 1e-2);
}

TEST_CASE("directional light shows the known L2 ringing", "[sh][irradiance]") {
  // Unit directional light (a delta of unit integral): L_k = Y_k(d).
  const glm::dvec3 d = glm::normalize(glm::dvec3(0.3, -0.5, 0.8));
  const glm::dvec3 e = glm::normalize(glm::cross(d, glm::dvec3(1, 0, 0)));
  const ShBasis y = sh_basis(d);
  Sh9Rgb sh;
  for (int k = 0; k < kShCount; ++k) sh.c[k] = Rgb(static_cast<float>(y[k]));

  CHECK(sh_irradiance(sh, d).x == Approx(1.0625).margin(kDirectionalTol));
  double min_e = 1e9, t_at_min = 0.0;
  constexpr int kSteps = 20000;
  for (int s = 0; s <= kSteps; ++s) {
    const double a = std::numbers::pi * s / kSteps;  // sweep n from d to -d through e
    const glm::dvec3 normal = std::cos(a) * d + std::sin(a) * e;
    const double got = sh_irradiance(sh, normal).y;
    CHECK(std::abs(got - directional_l2(std::cos(a))) < kDirectionalTol);
    if (got < min_e) min_e = got, t_at_min = std::cos(a);
  }
  CHECK(std::round(min_e * 1e4) / 1e4 == Approx(-0.0396).margin(1e-12));
  CHECK(min_e == Approx(directional_l2(-8.0 / 15.0)).margin(kDirectionalTol));
  CHECK(t_at_min == Approx(-8.0 / 15.0).margin(1e-3));
  CHECK(sh_irradiance(sh, -d).z == Approx(0.25 - 0.5 + 5.0 / 16.0).margin(kDirectionalTol));
}

TEST_CASE("a one-texel light through the cube projects to its basis values", "[sh][irradiance]") {
  // Radiance 1 / dOmega in one texel is a unit-integral light from that texel's centre, so
  // with exact weights the projection is Y_k(w_t) up to float rounding and E(w_t) = 1.0625.
  const int n = 16, i = 11, j = 4;
  const CubeFace face = CubeFace::NegX;
  CubeMap cube(n);
  cube.at(face, i, j) = Rgb(static_cast<float>(1.0 / cube_texel_solid_angle(n, i, j)));
  const glm::dvec3 d = cube_texel_direction(face, n, i, j);
  const Sh9Rgb sh = projector_for(n).project(cube);
  const ShBasis y = sh_basis(d);
  for (int k = 0; k < kShCount; ++k) CHECK(sh.c[k].x == Approx(y[k]).margin(1e-6));
  CHECK(sh_irradiance(sh, d).x == Approx(1.0625).margin(1e-5));
}
