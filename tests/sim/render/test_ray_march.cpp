// Ray marching: the pyramid marcher against the naive fixed-step reference and closed forms.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include <glm/geometric.hpp>

#include "sim/render/capture.h"
#include "sim/render/ray_march.h"
#include "sim/world/landmarks.h"
#include "sim/world/world.h"

using namespace ambisim;

namespace {

const World& test_world() {
  static const World w = [] {
    WorldParams p;
    p.seed = 11;
    p.size_m = {512.0, 512.0};
    return World(p);
  }();
  return w;
}

}  // namespace

TEST_CASE("a ray onto flat ground hits the top face at the closed-form distance", "[march]") {
  const World w = World::flat_test_world(4.0, {0.5f, 0.5f, 0.5f}, {1.0f, 1.0f, 1.0f}, 16.0, 0.25);
  const glm::dvec3 o(0.1, 0.2, 10.0), d = glm::normalize(glm::dvec3(0.6, 0.0, -0.8));
  for (Marcher m : {Marcher::accelerated, Marcher::naive}) {
    const RayHit h = march(w, o, d, m);
    REQUIRE(h.kind == HitKind::Column);
    CHECK(h.face == ColumnFace::Top);
    CHECK(h.t == Approx(12.5).epsilon(1e-12));
    // Hit point (7.6, 0.2, 0) lies in cell ((7.6 + 8) / 0.25, (0.2 + 8) / 0.25) = (62, 32).
    CHECK(h.ix == 62);
    CHECK(h.iy == 32);
  }
  // Upward rays see sky; rays from outside the grid land on the far ground plane at z = 0.
  CHECK(march_accelerated(w, o, {0.0, 0.0, 1.0}).kind == HitKind::Sky);
  const RayHit far = march_accelerated(w, {100.0, 0.0, 3.0}, glm::normalize(glm::dvec3(1, 0, -1)));
  CHECK(far.kind == HitKind::FarGround);
  CHECK(far.t == Approx(3.0 * std::sqrt(2.0)));
  // From outside toward the grid, but reaching z = 0 before the grid: far ground.
  const RayHit before =
      march_accelerated(w, {20.0, 0.0, 1.0}, glm::normalize(glm::dvec3(-1, 0, -1)));
  CHECK(before.kind == HitKind::FarGround);
  // From outside, entering the grid through its east side above the ground.
  const RayHit into = march_accelerated(w, {20.0, 0.1, 2.0}, glm::normalize(glm::dvec3(-6, 0, -1)));
  CHECK(into.kind == HitKind::Column);
  CHECK(into.t == Approx(2.0 * std::sqrt(37.0)));
}

TEST_CASE("accelerated and naive marchers agree on random rays", "[march]") {
  const World& w = test_world();
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const glm::dvec2 lo = w.min_xy(), hi = w.max_xy();
  int same = 0, total = 0, walls = 0;
  double worst_rel = 0.0;
  for (int k = 0; k < 4000; ++k) {
    const double x = lo.x + (hi.x - lo.x) * u(rng), y = lo.y + (hi.y - lo.y) * u(rng);
    const glm::dvec3 o(x, y, w.surface_height(x, y) + 0.5 + 60.0 * u(rng) * u(rng));
    const double z = -1.0 + 1.2 * u(rng), a = 6.283185307179586 * u(rng);
    const glm::dvec3 d(std::sqrt(1 - z * z) * std::cos(a), std::sqrt(1 - z * z) * std::sin(a), z);
    const glm::dvec3 o2 = capture_origin(w, o);
    const RayHit ha = march_accelerated(w, o2, d), hn = march_naive(w, o2, d);
    ++total;
    if (!ha.same_surface(hn)) continue;
    ++same;
    walls += ha.kind == HitKind::Column && ha.face != ColumnFace::Top;
    const Rgb la = hit_radiance(w, o2, d, ha), ln = hit_radiance(w, o2, d, hn);
    for (int c = 0; c < 3; ++c) {
      worst_rel = std::max(worst_rel, static_cast<double>(std::abs(la[c] - ln[c]) /
                                                          std::max(1e-6f, std::abs(ln[c]))));
    }
  }
  // Measured: 3999 / 4000 same surface (the naive quarter-cell step clips one corner).
  constexpr double kSameSurface = 0.999;
  constexpr double kRadianceRel = 1e-3;
  CHECK(static_cast<double>(same) / total >= kSameSurface);
  CHECK(worst_rel <= kRadianceRel);
  CHECK(walls > 100);  // the test exercises column walls, not just tops
}

TEST_CASE("captures agree between marchers on >= 99.9% of texels", "[march]") {
  const World& w = test_world();
  const WorldLandmarks l = find_landmarks(w);
  std::vector<glm::dvec3> points;
  if (!w.road().empty()) {
    const glm::dvec3 r = w.road().at(0.5 * w.road().length());
    points.push_back(r + glm::dvec3(0, 0, 1.5));
  }
  const glm::dvec2 c = 0.5 * (w.min_xy() + w.max_xy());
  points.push_back({c.x, c.y, w.surface_height(c.x, c.y) + 2.0});
  points.push_back({c.x + 100.0, c.y - 80.0, w.max_surface() + 40.0});  // in the air
  points.push_back({c.x - 150.0, c.y + 120.0, w.surface_height(c.x - 150, c.y + 120) + 25.0});
  if (l.forest_edge.found)
    points.push_back(l.forest_edge.edge - glm::dvec3(l.forest_edge.direction * 10.0, -2.0));
  long same = 0, total = 0;
  double worst_rel = 0.0;
  const int n = 32;
  for (const glm::dvec3& p : points) {
    const glm::dvec3 o = capture_origin(w, p);
    for (int f = 0; f < kCubeFaces; ++f) {
      for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
          const glm::dvec3 d = cube_texel_direction(static_cast<CubeFace>(f), n, i, j);
          const RayHit ha = march_accelerated(w, o, d), hn = march_naive(w, o, d);
          ++total;
          if (!ha.same_surface(hn)) continue;
          ++same;
          const Rgb la = hit_radiance(w, o, d, ha), ln = hit_radiance(w, o, d, hn);
          for (int k = 0; k < 3; ++k) {
            worst_rel = std::max(
                worst_rel, static_cast<double>(std::abs(la[k] - ln[k]) / std::max(1e-6f, ln[k])));
          }
        }
      }
    }
  }
  // Measured over 5 x 6144 texels: 100% same surface, radiance identical (relative 0).
  CHECK(static_cast<double>(same) / total >= 0.999);
  CHECK(worst_rel <= 1e-3);
}
