// Cube-map texel geometry: solid angles, face directions and how the faces fit together.
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

#include "sim/sh/cube_map.h"

using namespace ambisim;

namespace {

// Sum of the 6 N^2 closed-form solid angles vs 4 pi: measured <= 3.6e-14 for N <= 64.
constexpr double kSolidAngleSumTol = 1e-9;
// One texel vs a 64x64 midpoint rule of du dv / (1 + u^2 + v^2)^{3/2}: the midpoint rule's
// own error, measured max relative 6.0e-5 (N = 1), 1.5e-5 (N = 2), 9.4e-6 (N = 4).
constexpr double kTexelVsQuadratureRelTol = 1e-4;
constexpr double kDirectionTol = 1e-12;

double midpoint_texel_solid_angle(int n, int i, int j) {
  constexpr int kSub = 64;
  const double h = 2.0 / n / kSub, x0 = 2.0 * i / n - 1.0, y0 = 2.0 * j / n - 1.0;
  double s = 0.0;
  for (int b = 0; b < kSub; ++b) {
    for (int a = 0; a < kSub; ++a) {
      const double u = x0 + (a + 0.5) * h, v = y0 + (b + 0.5) * h;
      s += h * h / std::pow(1.0 + u * u + v * v, 1.5);
    }
  }
  return s;
}

const std::array<glm::dvec3, kCubeFaces> kAxes = {glm::dvec3(1, 0, 0), glm::dvec3(-1, 0, 0),
                                                  glm::dvec3(0, 1, 0), glm::dvec3(0, -1, 0),
                                                  glm::dvec3(0, 0, 1), glm::dvec3(0, 0, -1)};

}  // namespace

TEST_CASE("cube texel solid angles sum to 4 pi", "[sh][cube_map]") {
  for (int n : {1, 2, 3, 16, 64}) {
    double sum = 0.0;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) sum += kCubeFaces * cube_texel_solid_angle(n, i, j);
    INFO("N = " << n);
    CHECK(std::abs(sum - 4.0 * std::numbers::pi) < kSolidAngleSumTol);
  }
  // N = 1: each face is exactly a sixth of the sphere.
  CHECK(cube_texel_solid_angle(1, 0, 0) == Approx(4.0 * std::numbers::pi / 6.0).epsilon(1e-14));
}

TEST_CASE("each texel solid angle matches a sub-sampled Jacobian integral", "[sh][cube_map]") {
  for (int n : {1, 2, 4}) {
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        const double exact = cube_texel_solid_angle(n, i, j);
        INFO("N = " << n << " texel " << i << "," << j);
        CHECK(std::abs(midpoint_texel_solid_angle(n, i, j) / exact - 1.0) <
              kTexelVsQuadratureRelTol);
      }
    }
  }
  // A corner texel of a 16x16 face is (1/3)^{3/2} of the centre's, to the first order.
  const double ratio = cube_texel_solid_angle(16, 0, 0) / cube_texel_solid_angle(16, 8, 8);
  CHECK(ratio == Approx(std::pow(1.0 + 2.0 * (15.0 / 16) * (15.0 / 16), -1.5)).epsilon(0.02));
}

TEST_CASE("cube face centres are the six axes and texel directions are unit", "[sh][cube_map]") {
  for (int f = 0; f < kCubeFaces; ++f) {
    const auto face = static_cast<CubeFace>(f);
    const glm::dvec3 c = cube_face_direction(face, 0.0, 0.0);
    INFO("face " << kCubeFaceNames[f]);
    CHECK(glm::length(c - kAxes[f]) < kDirectionTol);
    // Odd N: the centre texel looks down the axis.
    CHECK(glm::length(cube_texel_direction(face, 5, 2, 2) - kAxes[f]) < kDirectionTol);
    // Texel (i, j) of N = 4 passes through (u, v) = (2 (i + 0.5) / 4 - 1, ...).
    const glm::dvec3 d = cube_texel_direction(face, 4, 3, 0);
    CHECK(std::abs(glm::length(d) - 1.0) < kDirectionTol);
    CHECK(glm::length(d - glm::normalize(cube_face_direction(face, 0.75, -0.75))) < kDirectionTol);
  }
}

TEST_CASE("cube faces are oriented alike and meet edge to edge", "[sh][cube_map]") {
  for (int f = 0; f < kCubeFaces; ++f) {
    const auto face = static_cast<CubeFace>(f);
    const glm::dvec3 o = cube_face_direction(face, 0, 0);
    const glm::dvec3 du = cube_face_direction(face, 1, 0) - o;
    const glm::dvec3 dv = cube_face_direction(face, 0, 1) - o;
    INFO("face " << kCubeFaceNames[f]);
    // Orthonormal in-plane axes and du x dv = outward axis: every face is seen the same way
    // from inside (no mirrored face), which the exact texel clipping also relies on.
    CHECK(std::abs(glm::dot(du, dv)) < kDirectionTol);
    CHECK(glm::length(glm::cross(du, dv) - kAxes[f]) < kDirectionTol);

    // Every point of every edge lies on the boundary of exactly one other face, and the
    // opposite face is never that neighbour.
    for (int e = 0; e < 4; ++e) {
      for (double t = -0.95; t < 1.0; t += 0.1) {
        const double u = e == 0 ? 1.0 : (e == 1 ? -1.0 : t);
        const double v = e == 2 ? 1.0 : (e == 3 ? -1.0 : t);
        const glm::dvec3 p = cube_face_direction(face, u, v);
        int owners = 0;
        for (int g = 0; g < kCubeFaces; ++g) {
          if (g == f) continue;
          const auto other = static_cast<CubeFace>(g);
          const glm::dvec3 og = cube_face_direction(other, 0, 0);
          if (std::abs(glm::dot(p, og) - 1.0) > kDirectionTol) continue;  // not on g's plane
          const double ug = glm::dot(p, cube_face_direction(other, 1, 0) - og);
          const double vg = glm::dot(p, cube_face_direction(other, 0, 1) - og);
          if (std::abs(ug) > 1.0 + kDirectionTol || std::abs(vg) > 1.0 + kDirectionTol) continue;
          CHECK(glm::length(cube_face_direction(other, ug, vg) - p) < kDirectionTol);
          CHECK(std::max(std::abs(ug), std::abs(vg)) == Approx(1.0).epsilon(1e-12));
          CHECK(glm::dot(og, o) == Approx(0.0).margin(kDirectionTol));
          ++owners;
        }
        CHECK(owners == 1);
      }
    }
  }
}

TEST_CASE("border texels of adjacent faces are neighbours on the sphere", "[sh][cube_map]") {
  // Across an edge the nearest texel centre of another face is as close as the nearest one
  // within the face (both ~ one texel pitch at the edge), never further.
  const int n = 8;
  for (int f = 0; f < kCubeFaces; ++f) {
    const auto face = static_cast<CubeFace>(f);
    for (int j = 0; j < n; ++j) {
      const glm::dvec3 d = cube_texel_direction(face, n, n - 1, j);  // u = +1 border column
      const double within = std::acos(glm::dot(d, cube_texel_direction(face, n, n - 2, j)));
      double across = 10.0;
      for (int g = 0; g < kCubeFaces; ++g) {
        if (g == f) continue;
        for (int jj = 0; jj < n; ++jj)
          for (int ii = 0; ii < n; ++ii)
            across = std::min(
                across,
                std::acos(std::min(
                    1.0, glm::dot(d, cube_texel_direction(static_cast<CubeFace>(g), n, ii, jj)))));
      }
      INFO("face " << kCubeFaceNames[f] << " row " << j);
      CHECK(across < 1.05 * within);
    }
  }
}
