// Velocity prediction: straight-line and along-the-road horizons, the focus segment distance.
#include <catch2/catch.hpp>
#include <cmath>

#include <glm/geometric.hpp>

#include "policies/core/velocity_prediction.h"
#include "sim/world/spline.h"

using namespace ambisim;

TEST_CASE("straight prediction is position + velocity x (latency + lookahead)", "[prediction]") {
  FrameContext ctx;
  ctx.camera_position = {10, 20, 5};
  ctx.camera_velocity = {30, 0, 0};
  ctx.dt = 1.0 / 60.0;
  ctx.faces_per_frame = 1.0;  // latency 6 frames = 0.1 s
  PredictionSettings s;
  s.enabled = true;
  s.lookahead_s = 0.5;
  const Focus f = make_focus(ctx, s);
  CHECK(f.ahead.x == Approx(10 + 30 * 0.6));
  CHECK(f.distance({10 + 9, 23, 5}) == Approx(3.0));  // beside the segment
  CHECK(f.distance({0, 20, 5}) == Approx(10.0));      // behind the camera
  ctx.camera_cut = true;                              // no prediction across a cut
  CHECK(make_focus(ctx, s).ahead == ctx.camera_position);
}

TEST_CASE("route prediction follows the road around a bend", "[prediction]") {
  std::vector<glm::dvec3> pts;
  for (int k = 0; k <= 32; ++k) {
    const double a = M_PI * k / 32.0;
    pts.push_back({100.0 * std::cos(a), 100.0 * std::sin(a), 0.0});
  }
  const Spline3 road(pts);
  WorldQueries wq;
  wq.road = &road;
  FrameContext ctx;
  ctx.world = &wq;
  ctx.camera_position = road.at(50.0);
  ctx.camera_velocity = 20.0 * road.tangent(50.0);
  // 2 s at 20 m/s along a circle of radius 100 m: 40 m of arc, still on the circle.
  const glm::dvec3 p = predict_position(ctx, 2.0, true, 15.0);
  CHECK(glm::length(p) == Approx(100.0).margin(0.05));
  CHECK(glm::length(p - road.at(90.0)) < 0.1);
  // The straight-line guess leaves the circle.
  CHECK(glm::length(predict_position(ctx, 2.0, false, 15.0)) > 101.0);
}
