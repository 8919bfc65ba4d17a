// Reference irradiance: exact per-texel clamped-cosine integrals, no SH truncation.
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "sim/sh/irradiance_reference.h"
#include "sim/sh/sh_projection.h"
#include "test_sh_support.h"

using namespace ambisim;

namespace {

// Exact integrals summed in double and returned as float: constant radiance and horizon-
// aligned sky/ground match their closed forms to float rounding, measured 3.8e-8 relative.
constexpr double kExactRelTol = 2e-7;
// One texel's integral vs a 64x64 midpoint rule of max(0, n . w) dOmega; the rule's error on
// the kink of texels the horizon cuts dominates: measured max 1.4e-5 of the texel's solid
// angle (N = 4).
constexpr double kTexelCosineTol = 5e-5;
// SH irradiance of an L2 radiance (exact for L2) vs the reference on the same rendered cube:
// both see the texel-constant radiance, measured max relative 9.2e-4 at N = 16, 5.8e-5 at 64.
constexpr double kL2AgreementTol16 = 1.5e-3;
constexpr double kL2AgreementTol64 = 1e-4;

double midpoint_texel_cosine(CubeFace face, int n, int i, int j, const glm::dvec3& normal) {
  constexpr int kSub = 64;
  const double h = 2.0 / n / kSub, x0 = 2.0 * i / n - 1.0, y0 = 2.0 * j / n - 1.0;
  double s = 0.0;
  for (int b = 0; b < kSub; ++b) {
    for (int a = 0; a < kSub; ++a) {
      const glm::dvec3 p = cube_face_direction(face, x0 + (a + 0.5) * h, y0 + (b + 0.5) * h);
      const double r = glm::length(p);
      s += std::max(0.0, glm::dot(normal, p) / r) * h * h / (r * r * r);
    }
  }
  return s;
}

std::vector<glm::dvec3> generic_normals() {
  std::vector<glm::dvec3> out = test::normals26();
  for (std::uint64_t k = 0; k < 10; ++k) {
    out.push_back(glm::normalize(glm::dvec3(test::hash_uniform(9, 3 * k, -1, 1),
                                            test::hash_uniform(9, 3 * k + 1, -1, 1),
                                            test::hash_uniform(9, 3 * k + 2, -1, 1))));
  }
  return out;
}

}  // namespace

TEST_CASE("texel cosine integral matches sub-sampled quadrature", "[sh][irradiance_ref]") {
  const int n = 4;
  double max_err = 0.0;
  for (const glm::dvec3& normal : {glm::normalize(glm::dvec3(0.2, -0.7, 0.4)), glm::dvec3(0, 0, 1),
                                   glm::normalize(glm::dvec3(1, 1, 0))}) {
    for (int f = 0; f < kCubeFaces; ++f) {
      for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
          const auto face = static_cast<CubeFace>(f);
          const double exact = texel_cosine_integral(face, n, i, j, normal);
          const double omega = cube_texel_solid_angle(n, i, j);
          CHECK(exact >= 0.0);
          CHECK(exact <= omega);
          const double err = std::abs(exact - midpoint_texel_cosine(face, n, i, j, normal));
          max_err = std::max(max_err, err / omega);
          CHECK(err < kTexelCosineTol * omega);
        }
      }
    }
  }
  CHECK(max_err > 0.0);
}

TEST_CASE("exact irradiance of constant radiance is pi L", "[sh][irradiance_ref]") {
  for (int n : {1, 2, 3, 16}) {
    const CubeMap cube = test::cube_from(n, [](const glm::dvec3&) { return Rgb(0.5f, 1, 2); });
    for (const glm::dvec3& normal : generic_normals()) {
      const Rgb e = exact_irradiance(cube, normal);
      INFO("N = " << n);
      CHECK(std::abs(e.x / (0.5 * std::numbers::pi) - 1.0) < kExactRelTol);
      CHECK(std::abs(e.y / std::numbers::pi - 1.0) < kExactRelTol);
      CHECK(std::abs(e.z / (2.0 * std::numbers::pi) - 1.0) < kExactRelTol);
    }
  }
  // The texel-centre rule max(0, n . w_t) dOmega_t is not exact: 1.3e-3 relative at N = 16
  // (measured), hence the clipped integral.
  const int n = 16;
  const glm::dvec3 normal = glm::normalize(glm::dvec3(1, 1, 1));
  double centre_rule = 0.0;
  for (int f = 0; f < kCubeFaces; ++f)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        centre_rule +=
            std::max(0.0,
                     glm::dot(normal, cube_texel_direction(static_cast<CubeFace>(f), n, i, j))) *
            cube_texel_solid_angle(n, i, j);
  CHECK(std::abs(centre_rule / std::numbers::pi - 1.0) > 1e-4);
}

TEST_CASE("exact irradiance of sky over ground is the closed form", "[sh][irradiance_ref]") {
  const Rgb sky(0.2f, 0.5f, 1.0f), ground(0.4f, 0.3f, 0.1f);
  for (int n : {2, 16}) {
    const CubeMap cube =
        test::cube_from(n, [&](const glm::dvec3& d) { return d.z > 0.0 ? sky : ground; });
    const std::vector<glm::dvec3> normals = generic_normals();
    const IrradianceIntegrator integrator(n, normals);
    const std::vector<Rgb> batch = integrator.integrate(cube);
    REQUIRE(batch.size() == normals.size());
    for (std::size_t m = 0; m < normals.size(); ++m) {
      const double c = normals[m].z;
      const glm::dvec3 want = std::numbers::pi * (glm::dvec3(sky) * (1.0 + c) / 2.0 +
                                                  glm::dvec3(ground) * (1.0 - c) / 2.0);
      const Rgb e = exact_irradiance(cube, normals[m]);
      for (int ch = 0; ch < 3; ++ch) {
        INFO("N = " << n << " normal " << m);
        CHECK(std::abs(e[ch] / want[ch] - 1.0) < kExactRelTol);
        CHECK(batch[m][ch] == e[ch]);  // same weights, same order: bit for bit
      }
    }
  }
}

TEST_CASE("SH irradiance of an L2 radiance agrees with the exact reference",
          "[sh][irradiance_ref]") {
  const Sh9Rgb sh = test::random_sh(21, 4.0f);  // positive-ish radiance, strong L1/L2 terms
  for (int n : {16, 64}) {
    const CubeMap cube =
        test::cube_from(n, [&](const glm::dvec3& d) { return sh_radiance(sh, d); });
    const std::vector<glm::dvec3> normals = test::normals26();
    const std::vector<Rgb> reference = IrradianceIntegrator(n, normals).integrate(cube);
    const Sh9Rgb projected = projector_for(n).project(cube);
    const double tol = n == 16 ? kL2AgreementTol16 : kL2AgreementTol64;
    for (std::size_t m = 0; m < normals.size(); ++m) {
      const Rgb analytic = sh_irradiance(sh, normals[m]);
      const Rgb from_cube = sh_irradiance(projected, normals[m]);
      for (int ch = 0; ch < 3; ++ch) {
        INFO("N = " << n << " normal " << m << " channel " << ch);
        CHECK(std::abs(reference[m][ch] / analytic[ch] - 1.0) < tol);
        CHECK(std::abs(from_cube[ch] / analytic[ch] - 1.0) < tol);
      }
    }
  }
}

TEST_CASE("reference irradiance rejects bad input", "[sh][irradiance_ref]") {
  CHECK_THROWS_AS(exact_irradiance(CubeMap(4), glm::dvec3(0, 0, 2)), std::invalid_argument);
  CHECK_THROWS_AS(IrradianceIntegrator(4, {glm::dvec3(1, 1, 0)}), std::invalid_argument);
  CHECK_THROWS_AS(IrradianceIntegrator(4, {glm::dvec3(0, 0, 1)}).integrate(CubeMap(8)),
                  std::invalid_argument);
}
