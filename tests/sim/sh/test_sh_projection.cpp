// Cube-map to SH projection: fast table path vs the double reference, round trips, and the
// thesis' uniform texel weight as a measured error source.
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

#include "sim/sh/sh_projection.h"
#include "test_sh_support.h"

using namespace ambisim;

namespace {

// Fast (float tables, float sums) vs naive (double): measured max coefficient difference
// relative to the largest coefficient 2.2e-7 for N in {1, 2, 3, 5, 16, 17}.
constexpr double kFastVsNaiveRelTol = 1e-6;
// Round trip of a random L2 function (coefficients in [-1, 1)) with exact weights: the
// texel-centre quadrature error, measured 1.44e-3 at N = 16 and 9.9e-5 at N = 64.
constexpr double kRoundTripTol16 = 2.5e-3;
constexpr double kRoundTripTol64 = 2e-4;

}  // namespace

TEST_CASE("fast SH projection equals the naive reference", "[sh][projection]") {
  for (int n : {1, 2, 3, 5, 16, 17}) {
    for (auto weighting : {TexelWeighting::exact_solid_angle, TexelWeighting::uniform_thesis}) {
      const CubeMap cube = test::random_cube(n, 100 + n);
      const Sh9Rgb naive = project_cube_naive(cube, weighting);
      const ShProjector projector(n, weighting);
      const Sh9Rgb fast = projector.project(cube);
      double scale = 0.0;
      for (const Rgb& c : naive.c)
        scale =
            std::max({scale, double(std::abs(c.x)), double(std::abs(c.y)), double(std::abs(c.z))});
      INFO("N = " << n << " weighting " << static_cast<int>(weighting));
      CHECK(test::max_abs_diff(fast, naive) < kFastVsNaiveRelTol * scale);

      // Face by face in order is the same computation as project(), bit for bit.
      Sh9Rgb by_face;
      for (int f = 0; f < kCubeFaces; ++f)
        projector.accumulate_face(cube, static_cast<CubeFace>(f), by_face);
      CHECK(by_face == fast);
    }
  }
}

TEST_CASE("single faces project to their share of the whole", "[sh][projection]") {
  // Radiance only on -Y: accumulate_face(-Y) alone reproduces the full projection, and the
  // other faces add exactly nothing.
  CubeMap cube = test::random_cube(16, 7);
  for (int f = 0; f < kCubeFaces; ++f) {
    if (f == static_cast<int>(CubeFace::NegY)) continue;
    for (int j = 0; j < 16; ++j)
      for (int i = 0; i < 16; ++i) cube.at(static_cast<CubeFace>(f), i, j) = Rgb(0.0f);
  }
  const ShProjector& projector = projector_for(16);
  Sh9Rgb one;
  projector.accumulate_face(cube, CubeFace::NegY, one);
  CHECK(one == projector.project(cube));
  // The -Y face sits around direction (0, -1, 0): Y1-1 = k1 y is negative there.
  CHECK(one.c[1].x < 0.0f);
  CHECK(test::max_abs_diff(one, project_cube_naive(cube)) < 1e-5);
}

TEST_CASE("SH round trip through a rendered cube", "[sh][projection]") {
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const Sh9Rgb sh = test::random_sh(seed);
    for (int n : {16, 64}) {
      const CubeMap cube =
          test::cube_from(n, [&](const glm::dvec3& d) { return sh_radiance(sh, d); });
      const double tol = n == 16 ? kRoundTripTol16 : kRoundTripTol64;
      INFO("seed " << seed << " N = " << n);
      CHECK(test::max_abs_diff(projector_for(n).project(cube), sh) < tol);
      CHECK(test::max_abs_diff(project_cube_naive(cube), sh) < tol);
    }
  }
}

TEST_CASE("thesis uniform texel weight is measurably worse", "[sh][projection]") {
  // Round trip at N = 16: uniform weights give a coefficient error of 0.22 (measured) against
  // 1.4e-3 with exact solid angles, and it does not shrink with N (0.195 at N = 64): a bias,
  // not a quadrature error.
  const Sh9Rgb sh = test::random_sh(5);
  const CubeMap cube = test::cube_from(16, [&](const glm::dvec3& d) { return sh_radiance(sh, d); });
  const double exact_err = test::max_abs_diff(project_cube_naive(cube), sh);
  const double uniform_err =
      test::max_abs_diff(project_cube_naive(cube, TexelWeighting::uniform_thesis), sh);
  CHECK(uniform_err > 50.0 * exact_err);
  CHECK(uniform_err > 0.05);
  CHECK(test::max_abs_diff(ShProjector(16, TexelWeighting::uniform_thesis).project(cube), sh) ==
        Approx(uniform_err).epsilon(1e-3));

  // A constant cube does not expose it: by the cube's symmetries every non-constant
  // coefficient cancels and the uniform weights still sum to 4 pi (both errors ~1e-7).
  const CubeMap flat = test::cube_from(16, [](const glm::dvec3&) { return Rgb(1.0f); });
  const Sh9Rgb u = projector_for(16, TexelWeighting::uniform_thesis).project(flat);
  CHECK(u.c[0].x == Approx(std::sqrt(4.0 * std::numbers::pi)).epsilon(1e-6));
  for (int k = 1; k < kShCount; ++k) CHECK(std::abs(u.c[k].x) < 1e-6);
}

TEST_CASE("projector_for caches one projector per size and weighting", "[sh][projection]") {
  const ShProjector* a = &projector_for(8);
  CHECK(&projector_for(8) == a);
  CHECK(&projector_for(8, TexelWeighting::uniform_thesis) != a);
  CHECK(projector_for(8, TexelWeighting::uniform_thesis).weighting() ==
        TexelWeighting::uniform_thesis);
  CHECK(a->face_size() == 8);

  // Concurrent first use of a new size yields one shared object.
  std::array<const ShProjector*, 4> seen{};
  std::vector<std::thread> threads;
  for (std::size_t t = 0; t < seen.size(); ++t)
    threads.emplace_back([&seen, t] { seen[t] = &projector_for(12); });
  for (auto& th : threads) th.join();
  CHECK(std::set<const ShProjector*>(seen.begin(), seen.end()).size() == 1);
}

TEST_CASE("projection rejects mismatched cubes", "[sh][projection]") {
  CHECK_THROWS_AS(ShProjector(0), std::invalid_argument);
  CHECK_THROWS_AS(projector_for(16).project(CubeMap(8)), std::invalid_argument);
  Sh9Rgb acc;
  CHECK_THROWS_AS(projector_for(16).accumulate_face(CubeMap(15), CubeFace::PosX, acc),
                  std::invalid_argument);
  CHECK_THROWS_AS(project_cube_naive(CubeMap()), std::invalid_argument);
}
