#include "sim/sh/irradiance_reference.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include <glm/geometric.hpp>

namespace ambisim {
namespace {

constexpr double kUnitTolerance = 1e-6;

void check_unit(const glm::dvec3& n) {
  if (!(std::abs(glm::length(n) - 1.0) <= kUnitTolerance)) {
    throw std::invalid_argument("irradiance: normal must be a unit vector");
  }
}

void check_cube(const CubeMap& cube) {
  if (cube.size < 1 ||
      cube.texel.size() != static_cast<std::size_t>(kCubeFaces) * cube.size * cube.size) {
    throw std::invalid_argument("irradiance: malformed cube map");
  }
}

}  // namespace

double texel_cosine_integral(CubeFace face, int size, int i, int j, const glm::dvec3& n) {
  const double x0 = 2.0 * i / size - 1.0, x1 = 2.0 * (i + 1) / size - 1.0;
  const double y0 = 2.0 * j / size - 1.0, y1 = 2.0 * (j + 1) / size - 1.0;
  // Corners counter-clockwise seen from outside (every face has du x dv pointing outward).
  const std::array<glm::dvec3, 4> quad = {
      cube_face_direction(face, x0, y0), cube_face_direction(face, x1, y0),
      cube_face_direction(face, x1, y1), cube_face_direction(face, x0, y1)};
  // Clip the flat quad to n . p >= 0. The half-space is a cone through the origin, so the
  // radial projection of the clipped quad is exactly the clipped spherical texel.
  std::array<glm::dvec3, 8> poly{};
  int count = 0;
  for (int k = 0; k < 4; ++k) {
    const glm::dvec3& p = quad[k];
    const glm::dvec3& q = quad[(k + 1) % 4];
    const double dp = glm::dot(n, p), dq = glm::dot(n, q);
    if (dp >= 0.0) poly[count++] = p;
    if ((dp >= 0.0) != (dq >= 0.0)) poly[count++] = p + (dp / (dp - dq)) * (q - p);
  }
  if (count < 3) return 0.0;
  // Lambert: integral of n . w over a spherical polygon = 1/2 sum over edges of the edge's
  // arc angle times n . (unit normal of the edge's great-circle plane).
  double sum = 0.0;
  for (int k = 0; k < count; ++k) {
    const glm::dvec3& a = poly[k];
    const glm::dvec3& b = poly[(k + 1) % count];
    const glm::dvec3 c = glm::cross(a, b);
    const double len = glm::length(c);
    if (len <= 0.0) continue;  // repeated vertex on the clip plane: zero-length edge
    sum += std::atan2(len, glm::dot(a, b)) * glm::dot(n, c) / len;
  }
  return std::max(0.0, 0.5 * sum);
}

Rgb exact_irradiance(const CubeMap& cube, const glm::dvec3& unit_normal) {
  check_cube(cube);
  check_unit(unit_normal);
  glm::dvec3 e(0.0);
  for (int f = 0; f < kCubeFaces; ++f) {
    const auto face = static_cast<CubeFace>(f);
    for (int j = 0; j < cube.size; ++j) {
      for (int i = 0; i < cube.size; ++i) {
        const double w = texel_cosine_integral(face, cube.size, i, j, unit_normal);
        if (w > 0.0) e += w * glm::dvec3(cube.at(face, i, j));
      }
    }
  }
  return Rgb(e);
}

IrradianceIntegrator::IrradianceIntegrator(int face_size, std::vector<glm::dvec3> unit_normals)
    : size_(face_size), normals_(std::move(unit_normals)) {
  if (face_size < 1) throw std::invalid_argument("IrradianceIntegrator: face_size must be >= 1");
  const int n = size_;
  begin_.push_back(0);
  for (const glm::dvec3& normal : normals_) {
    check_unit(normal);
    for (int f = 0; f < kCubeFaces; ++f) {
      const auto face = static_cast<CubeFace>(f);
      for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
          const double w = texel_cosine_integral(face, n, i, j, normal);
          if (w > 0.0) {
            texel_.push_back(static_cast<std::uint32_t>(
                (static_cast<std::size_t>(f) * n + static_cast<std::size_t>(j)) * n + i));
            weight_.push_back(w);
          }
        }
      }
    }
    begin_.push_back(texel_.size());
  }
}

std::vector<Rgb> IrradianceIntegrator::integrate(const CubeMap& cube) const {
  check_cube(cube);
  if (cube.size != size_) throw std::invalid_argument("IrradianceIntegrator: cube size mismatch");
  std::vector<Rgb> out(normals_.size());
  for (std::size_t m = 0; m < normals_.size(); ++m) {
    double r = 0.0, g = 0.0, b = 0.0;
    for (std::size_t e = begin_[m]; e < begin_[m + 1]; ++e) {
      const Rgb& l = cube.texel[texel_[e]];
      const double w = weight_[e];
      r += w * l.x;
      g += w * l.y;
      b += w * l.z;
    }
    out[m] = Rgb(static_cast<float>(r), static_cast<float>(g), static_cast<float>(b));
  }
  return out;
}

}  // namespace ambisim
