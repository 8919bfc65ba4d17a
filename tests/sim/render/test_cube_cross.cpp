// The cube-cross picture: layout, seam continuity, up is up, face colours.
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <optional>
#include <vector>

#include <glm/geometric.hpp>

#include "sim/colour/cielab.h"
#include "sim/colour/tone_map.h"
#include "sim/render/cube_cross.h"

using ambisim::CubeFace;
using ambisim::CubeMap;
using ambisim::Rgb;

namespace {
// Directions of image-adjacent pixels (same face or across an attached seam) differ by at most
// this many nominal texel angles (90 deg / N). Measured for N = 5: 1.21 within a face (centre
// texels, atan(0.4) = 21.8 deg), 0.71 across seams; for N = 16: 1.27 and 0.66.
constexpr double kMaxNeighbourTexelAngles = 2.0;

constexpr int kFirstCode = 60;  // grey codes 60.. identify texels; 0 stays "empty"

double texel_angle(int n) { return 0.5 * std::numbers::pi / n; }

double angle_between(const glm::dvec3& a, const glm::dvec3& b) {
  return std::acos(std::clamp(glm::dot(a, b), -1.0, 1.0));
}

// Each texel a grey whose tone-mapped 8-bit code (exposure 1) is kFirstCode + its index.
CubeMap coded_cube(int n) {
  CubeMap cube(n);
  for (std::size_t k = 0; k < cube.texel.size(); ++k) {
    const double t = ambisim::srgb_decode((kFirstCode + static_cast<double>(k)) / 255.0);
    cube.texel[k] = Rgb(static_cast<float>(t / (1.0 - t)));  // inverse Reinhard of a grey
  }
  return cube;
}

struct Decoded {
  CubeFace face;
  int i, j;
};

// Texel shown at pixel (x, y) of a coded cube's cross, or nullopt for black.
std::optional<Decoded> decode(const ambisim::ImageRgb8& img, int n, int x, int y) {
  const std::uint8_t* p = img.pixel(x, y);
  REQUIRE(p[0] == p[1]);
  REQUIRE(p[1] == p[2]);
  if (p[0] == 0) return std::nullopt;
  const int k = p[0] - kFirstCode;
  REQUIRE(k >= 0);
  REQUIRE(k < 6 * n * n);
  return Decoded{static_cast<CubeFace>(k / (n * n)), k % n, (k / n) % n};
}

glm::dvec3 dir(const Decoded& d, int n) {
  return ambisim::cube_texel_direction(d.face, n, d.i, d.j);
}
}  // namespace

TEST_CASE("cube cross: size, blocks, every texel exactly once, layout helper agrees",
          "[colour][cube_cross]") {
  const int n = 5, scale = 3;
  const auto img = ambisim::cube_cross_image(coded_cube(n), 1.0, scale);
  REQUIRE(img.width == 4 * n * scale);
  REQUIRE(img.height == 3 * n * scale);
  std::vector<int> seen(6 * n * n, 0);
  int empty = 0;
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) {
      const auto d = decode(img, n, x, y);
      const auto ref = ambisim::cube_cross_texel(n, x / scale, y / scale);
      REQUIRE(d.has_value() == ref.has_value());
      if (!d) {
        ++empty;
        continue;
      }
      CHECK(d->face == ref->face);
      CHECK(d->i == ref->i);
      CHECK(d->j == ref->j);
      if (x % scale == 0 && y % scale == 0) ++seen[(int(d->face) * n + d->j) * n + d->i];
    }
  }
  for (int c : seen) CHECK(c == 1);
  CHECK(empty == 6 * n * n * scale * scale);
}

TEST_CASE("cube cross: neighbouring pixels show neighbouring directions, across seams too",
          "[colour][cube_cross]") {
  const int n = 5;
  const auto img = ambisim::cube_cross_image(coded_cube(n), 1.0, 1);
  int seam_pairs = 0;
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) {
      const auto a = decode(img, n, x, y);
      if (!a) continue;
      for (const auto& [dx, dy] : {std::pair{1, 0}, std::pair{0, 1}}) {
        if (x + dx >= img.width || y + dy >= img.height) continue;
        const auto b = decode(img, n, x + dx, y + dy);
        if (!b) continue;
        INFO("pixel " << x << "," << y << " faces " << int(a->face) << "," << int(b->face));
        if (a->face != b->face) ++seam_pairs;
        CHECK(angle_between(dir(*a, n), dir(*b, n)) <= kMaxNeighbourTexelAngles * texel_angle(n));
      }
    }
  }
  // Attached seams: -X|+Y, +Y|+X, +X|-Y (n pairs each) and +Z/+Y, +Y/-Z (n each).
  CHECK(seam_pairs == 5 * n);

  // Same check on the layout helper at a finer resolution (no image needed).
  const int m = 16;
  for (int y = 0; y < 3 * m; ++y) {
    for (int x = 0; x < 4 * m; ++x) {
      const auto a = ambisim::cube_cross_texel(m, x, y);
      if (!a) continue;
      for (const auto& [dx, dy] : {std::pair{1, 0}, std::pair{0, 1}}) {
        const auto b = ambisim::cube_cross_texel(m, x + dx, y + dy);
        if (!b) continue;
        const double ang = angle_between(ambisim::cube_texel_direction(a->face, m, a->i, a->j),
                                         ambisim::cube_texel_direction(b->face, m, b->i, b->j));
        CHECK(ang <= kMaxNeighbourTexelAngles * texel_angle(m));
      }
    }
  }
}

TEST_CASE("cube cross: up is up in the middle band", "[colour][cube_cross]") {
  const int n = 5;
  const auto img = ambisim::cube_cross_image(coded_cube(n), 1.0, 1);
  for (int x = 0; x < 4 * n; ++x) {
    const auto top = decode(img, n, x, n);             // first row of the middle band
    const auto bottom = decode(img, n, x, 2 * n - 1);  // last row
    REQUIRE(top);
    REQUIRE(bottom);
    CHECK(dir(*top, n).z > 0.5);
    CHECK(dir(*bottom, n).z < -0.5);
  }
  // The +Z cell's centre is straight up, the -Z cell's straight down.
  CHECK(dir(*decode(img, n, n + n / 2, n / 2), n).z == Approx(1.0));
  CHECK(dir(*decode(img, n, n + n / 2, 2 * n + n / 2), n).z == Approx(-1.0));
}

TEST_CASE("cube cross: face centres of a direction-coloured cube", "[colour][cube_cross]") {
  // Radiance 0.5 + 0.5 d (a normal-map colouring); odd n puts a texel exactly on each axis.
  const int n = 5, scale = 4;
  CubeMap cube(n);
  for (int f = 0; f < 6; ++f) {
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        const auto d = ambisim::cube_texel_direction(static_cast<CubeFace>(f), n, i, j);
        cube.at(static_cast<CubeFace>(f), i, j) = Rgb(0.5 + 0.5 * d);
      }
    }
  }
  const auto img = ambisim::cube_cross_image(cube, 1.0, scale);
  struct Cell {
    int col, row;
    glm::dvec3 axis;  // what the viewer should see there
  };
  const std::array<Cell, 6> cells = {{{1, 0, {0, 0, 1}},     // sky
                                      {0, 1, {-1, 0, 0}},    // west
                                      {1, 1, {0, 1, 0}},     // north
                                      {2, 1, {1, 0, 0}},     // east
                                      {3, 1, {0, -1, 0}},    // south
                                      {1, 2, {0, 0, -1}}}};  // ground
  for (const Cell& c : cells) {
    INFO("cell " << c.col << "," << c.row);
    const std::uint8_t* p =
        img.pixel((c.col * n + n / 2) * scale + 1, (c.row * n + n / 2) * scale + 2);
    const auto want = ambisim::to_srgb8(Rgb(0.5 + 0.5 * c.axis), 1.0);
    CHECK(p[0] == want[0]);
    CHECK(p[1] == want[1]);
    CHECK(p[2] == want[2]);
    // Independent of the tone map: the channel of the axis is the brightest (or darkest).
    for (int k = 0; k < 3; ++k) {
      if (c.axis[k] > 0) CHECK(p[k] > p[(k + 1) % 3]);
      if (c.axis[k] < 0) CHECK(p[k] < p[(k + 1) % 3]);
    }
  }
  for (const auto& [col, row] : {std::pair{0, 0}, std::pair{2, 0}, std::pair{3, 0}, std::pair{0, 2},
                                 std::pair{2, 2}, std::pair{3, 2}}) {
    const std::uint8_t* p = img.pixel((col * n + n / 2) * scale, (row * n + n / 2) * scale);
    CHECK((p[0] | p[1] | p[2]) == 0);
  }
}
