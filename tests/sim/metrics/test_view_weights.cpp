// What the player sees: the receivers' screen weights and the normals' visible shares.
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "sim/metrics/view_weights.h"

using namespace ambisim;

namespace {
constexpr double kSrTol = 1e-12;  // steradians, closed forms in double
const ViewSpec kView{};           // 70 degrees horizontal, 16:9
}  // namespace

TEST_CASE("a sphere's solid angle: the closed form and its limits", "[metrics][view]") {
  // 2 pi (1 - cos(asin(r/d))): r/d = 1/2 gives 2 pi (1 - sqrt(3)/2).
  CHECK(sphere_solid_angle(1.0, 2.0) ==
        Approx(2.0 * std::numbers::pi * (1.0 - std::sqrt(3.0) / 2.0)).margin(kSrTol));
  // Far away: pi r^2 / d^2 to second order.
  CHECK(sphere_solid_angle(1.0, 1e4) == Approx(std::numbers::pi * 1e-8).epsilon(1e-8));
  // Touching or containing the camera: not seen.
  CHECK(sphere_solid_angle(1.0, 1.0) == 0.0);
  CHECK(sphere_solid_angle(1.0, 0.5) == 0.0);
}

TEST_CASE("a receiver behind the camera weighs 0, one at twice the distance a quarter",
          "[metrics][view]") {
  const CameraView v(kView, {0, 0, 0}, {1, 0, 0});
  const double near = v.screen_weight({50, 0, 0}, 1.0);
  const double far = v.screen_weight({100, 0, 0}, 1.0);
  CHECK(near > 0.0);
  // Exactly (1 - sqrt(1 - 1/100^2)) / (1 - sqrt(1 - 1/50^2)) = 0.250019; a quarter to 1e-4.
  CHECK(far / near == Approx(0.25).margin(1e-4));
  CHECK(v.screen_weight({-50, 0, 0}, 1.0) == 0.0);  // behind
  CHECK(v.screen_weight({0, 50, 0}, 1.0) == 0.0);   // beside, 90 degrees off the axis
}

TEST_CASE("the frustum: 70 degrees across, 16:9, spheres count while they touch it",
          "[metrics][view]") {
  const CameraView v(kView, {0, 0, 0}, {1, 0, 0});
  const double half_w = 35.0 * std::numbers::pi / 180.0;
  const double half_h = std::atan(std::tan(half_w) * 9.0 / 16.0);
  // Just inside and just outside the left edge (+y is left when looking along +x, z up).
  const auto at = [](double azimuth, double elevation, double d) {
    return glm::dvec3(d * std::cos(elevation) * std::cos(azimuth),
                      d * std::cos(elevation) * std::sin(azimuth), d * std::sin(elevation));
  };
  CHECK(v.sees_sphere(at(half_w - 0.01, 0, 100), 0.01));
  CHECK_FALSE(v.sees_sphere(at(half_w + 0.01, 0, 100), 0.01));
  // A sphere whose centre is outside but which reaches into the frustum still counts.
  CHECK(v.sees_sphere(at(half_w + 0.01, 0, 100), 2.0));
  // Vertical: 9/16 of the horizontal tangent.
  CHECK(v.sees_sphere(at(0, half_h - 0.01, 100), 0.01));
  CHECK_FALSE(v.sees_sphere(at(0, half_h + 0.01, 100), 0.01));
  CHECK(v.sees_sphere(at(0, -(half_h - 0.01), 100), 0.01));
  CHECK_FALSE(v.sees_sphere(at(0, -(half_h + 0.01), 100), 0.01));
}

TEST_CASE("a normal facing away from the camera weighs 0", "[metrics][view]") {
  const glm::dvec3 to_camera(0, 0, 1);
  CHECK(normal_visible_share({0, 0, 1}, to_camera) == 1.0);
  CHECK(normal_visible_share({0, 0, -1}, to_camera) == 0.0);
  CHECK(normal_visible_share({1, 0, 0}, to_camera) == 0.0);
  const double s = 1.0 / std::sqrt(2.0);
  CHECK(normal_visible_share({s, 0, s}, to_camera) == Approx(s).margin(1e-15));
}

TEST_CASE("the view's frame: looking straight down still has a frame", "[metrics][view]") {
  const CameraView down(kView, {0, 0, 100}, {0, 0, -1});
  CHECK(down.sees_sphere({0, 0, 0}, 1.0));
  CHECK_FALSE(down.sees_sphere({0, 0, 200}, 1.0));
  const CameraView still(kView, {0, 0, 0}, {0, 0, 0});  // no heading: looks along +x
  CHECK(still.sees_sphere({10, 0, 0}, 1.0));
}
