// Camera paths: closed-form distances for each speed profile, lane geometry on straight and
// curved roads, cuts on the exact frame.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>

#include <glm/geometric.hpp>

#include "sim/scenario/camera_path.h"
#include "sim/scenario/frame_schedule.h"

using namespace ambisim;

namespace {

// Positions on a 2-point spline are exact up to float sums (the mirrored end points make the
// parameter uniform in arc length). Measured relative errors: position 3e-15, velocity 9e-13
// (the tangent is a chord over +-0.25 m), exponential distance profile 4e-13.
constexpr double kStraightRel = 1e-9;
// On curves at() interpolates the arc-length table (1.7e-4 m, test_spline). Measured here:
// lateral offset from the nearest centre-line point 3.3e-4 m; height above the road and
// squareness to it at the travelled arc length 2e-14 m.
constexpr double kLaneTol = 1e-3;  // m
// Analytic velocity against a central difference of positions over +-kFdStep: measured
// 1.7e-3 m/s on the curved road (at()'s table interpolation noise over 3 m of travel; a
// 0.01 s step gives 6e-3 from that noise, a 0.2 s step 0.07 from the curvature term).
constexpr double kVelocityTol = 0.005;  // m/s
constexpr double kFdStep = 0.05;        // s

CameraPathRecord straight(glm::dvec3 a, glm::dvec3 b, double speed) {
  CameraPathRecord r;
  r.points = {a, b};
  r.speed.speed_mps = speed;
  return r;
}

CameraPathRecord parse_camera_path(const char* text) {
  const auto j = nlohmann::json::parse(text);
  ObjectReader r(j, "test.json", "/camera");
  return parse_camera_path(r);
}

TerrainQueries flat() {
  TerrainQueries t;
  t.ground_height = [](double, double) { return 0.0; };
  return t;
}

}  // namespace

TEST_CASE("constant speed along a straight path is start + v t", "[camera]") {
  const glm::dvec3 a(10, 20, 30), b(610, 820, 30);  // 1000 m long
  const glm::dvec3 dir = (b - a) / 1000.0;
  const CameraPath path(straight(a, b, 25.0), flat());
  REQUIRE(path.course_length() == Approx(1000.0).epsilon(kStraightRel));
  for (double t : {0.0, 0.01, 3.7, 17.25, 39.99}) {
    const CameraState s = path.state(t, t);
    const glm::dvec3 expect = a + 25.0 * t * dir;
    CHECK(glm::length(s.position - expect) <= kStraightRel * glm::length(expect));
    CHECK(glm::length(s.velocity - 25.0 * dir) <= kStraightRel * 25.0);
    CHECK_FALSE(s.cut);
  }
  // Hold at the end: 40 s reach the end, then the camera stops.
  const CameraState end = path.state(100.0, 99.0);
  CHECK(glm::length(end.position - b) <= kStraightRel * glm::length(b));
  CHECK(glm::length(end.velocity) == 0.0);
}

TEST_CASE("a speed ramp over time integrates to the closed-form distance", "[camera]") {
  // 10 m/s at t = 2, rising linearly to 30 m/s at t = 12, constant around that.
  CameraPathRecord r = straight({0, 0, 0}, {5000, 0, 0}, 0.0);
  r.speed.axis = SpeedProfileRecord::Axis::time;
  r.speed.points = {{2.0, 10.0}, {12.0, 30.0}};
  const CameraPath path(r, flat());
  auto distance = [](double t) {  // closed form
    if (t <= 2.0) return 10.0 * t;
    if (t <= 12.0) return 20.0 + 10.0 * (t - 2.0) + (t - 2.0) * (t - 2.0);
    return 20.0 + 200.0 + 30.0 * (t - 12.0);
  };
  for (double t : {1.0, 2.0, 4.5, 7.0, 12.0, 20.0}) {
    const CameraState s = path.state(t, t);
    CHECK(s.position.x == Approx(distance(t)).epsilon(kStraightRel));
  }
  CHECK(path.state(7.0, 7.0).velocity.x == Approx(20.0).epsilon(kStraightRel));
}

TEST_CASE("a speed profile over distance integrates exponentially", "[camera]") {
  // v(s) = 10 + 0.1 s up to s = 200 (30 m/s): s(t) = 100 (e^{0.1 t} - 1), reached at ln 3 / 0.1.
  const auto r = parse_camera_path(R"({"points": [[0,0,0],[5000,0,0]],
      "speed_profile": [{"arc_length_m": 0, "speed_mps": 10}, {"arc_length_m": 200, "speed_mps": 30}]})");
  const CameraPath path(r, flat());
  const double t200 = std::log(3.0) / 0.1;
  for (double t : {0.5, 3.0, 8.0}) {
    const CameraState s = path.state(t, t);
    CHECK(s.position.x == Approx(100.0 * std::expm1(0.1 * t)).epsilon(kStraightRel));
    CHECK(s.velocity.x == Approx(10.0 + 0.1 * s.position.x).epsilon(kStraightRel));
  }
  CHECK(path.state(t200 + 2.0, t200).position.x == Approx(260.0).epsilon(kStraightRel));
}

TEST_CASE("road path keeps its lane offset and height on straight and curved roads", "[camera]") {
  SECTION("straight road, both directions") {
    const Spline3 road({{0, 0, 5}, {2000, 0, 5}});
    TerrainQueries t = flat();
    t.road = &road;
    t.road_width = 14.0;  // default lane offset 3.5 m
    CameraPathRecord r;
    r.type = CameraPathRecord::Type::road;
    r.speed.speed_mps = 30.0;
    const CameraState fwd = CameraPath(r, t).state(10.0, 10.0);
    CHECK(fwd.position.x == Approx(300.0).epsilon(kStraightRel));
    CHECK(fwd.position.y == Approx(-3.5).epsilon(kStraightRel));  // right of +x is -y
    CHECK(fwd.position.z == Approx(6.5).epsilon(kStraightRel));
    CHECK(fwd.velocity.x == Approx(30.0).epsilon(kStraightRel));
    r.direction = -1;
    r.start_arc_length_m = 2000.0;
    r.lane_offset_m = 1.75;
    const CameraState back = CameraPath(r, t).state(10.0, 10.0);
    CHECK(back.position.x == Approx(1700.0).epsilon(kStraightRel));
    CHECK(back.position.y == Approx(1.75).epsilon(kStraightRel));
    CHECK(back.velocity.x == Approx(-30.0).epsilon(kStraightRel));
  }
  SECTION("curved, climbing road") {
    // A half circle of radius 300 m climbing 2 m per 100 m of arc.
    std::vector<glm::dvec3> pts;
    for (int k = 0; k <= 12; ++k) {
      const double a = M_PI * k / 12.0;
      pts.push_back({300.0 * std::cos(a), 300.0 * std::sin(a), 0.02 * 300.0 * a});
    }
    const Spline3 road(pts);
    TerrainQueries t = flat();
    t.road = &road;
    for (int dir : {1, -1}) {
      CameraPathRecord r;
      r.type = CameraPathRecord::Type::road;
      r.lane_offset_m = 1.75;
      r.height_m = 1.5;
      r.direction = dir;
      r.start_arc_length_m = dir > 0 ? 0.0 : road.length();
      r.speed.speed_mps = 30.0;
      const CameraPath path(r, t);
      for (double time = 1.0; time < 30.0; time += 1.7) {
        const CameraState s = path.state(time, time);
        // Oracle 1: the nearest centre-line point (independent of how the path walks the
        // road) is 1.75 m away horizontally. Measured max error 3.3e-4 m.
        const glm::dvec3 near = road.at(road.closest_s(s.position));
        const glm::dvec3 side = s.position - near;
        CHECK(std::hypot(side.x, side.y) == Approx(1.75).margin(kLaneTol));
        // Oracle 2: at the arc length travelled, 30 t from the start, the camera is 1.5 m
        // above the road and square to it. (closest_s in 3D slides 0.03 m along the 2 %
        // grade because the camera is above the road, so it is not the oracle for height.)
        const double sc = r.start_arc_length_m + dir * 30.0 * time;
        const glm::dvec3 off = s.position - road.at(sc);
        CHECK(off.z == Approx(1.5).margin(kLaneTol));
        const double along = glm::dot(glm::dvec3(off.x, off.y, 0.0), road.tangent(sc));
        CHECK(std::abs(along) < kLaneTol);
        // Right of travel: the road turns left (counter-clockwise) for dir +1, so that lane
        // lies outside the curve, the other inside. (The spline strays up to 0.03 m from the
        // circle through its points, so the circle is not an oracle at this tolerance.)
        const double outward = std::hypot(s.position.x, s.position.y) - std::hypot(near.x, near.y);
        CHECK(outward == Approx(dir > 0 ? 1.75 : -1.75).margin(kLaneTol));
        const glm::dvec3 fd = (path.state(time + kFdStep, time).position -
                               path.state(time - kFdStep, time).position) /
                              (2.0 * kFdStep);
        CHECK(glm::length(s.velocity - fd) < kVelocityTol);
      }
    }
  }
}

TEST_CASE("explicit cuts jump on the exact frame with cut = true", "[camera]") {
  const auto r = parse_camera_path(R"({"points": [[0,0,0],[5000,0,0]], "speed_mps": 10,
      "cuts": [{"time_s": 2.5, "to_arc_length_m": 700},
               {"time_s": 4.0, "jump_ahead_m": 100},
               {"time_s": 6.0, "to_position": [3000, 40, 0]}]})");
  const CameraPath path(r, flat());
  FrameScheduleRecord fr;
  fr.segments = {{0.0, 100.0, false}};
  fr.duration_s = 8.0;
  const FrameSchedule schedule(fr);
  FrameClock clock(schedule);
  Frame f;
  double prev = 0.0;
  std::vector<std::int64_t> cut_frames;
  while (clock.next(f)) {
    const CameraState s = path.state(f.time, prev);
    if (s.cut) cut_frames.push_back(f.index);
    prev = f.time;
    if (f.index == 250) CHECK(s.position.x == Approx(700.0).epsilon(kStraightRel));
    if (f.index == 399) CHECK(s.position.x == Approx(700.0 + 14.9).epsilon(kStraightRel));
    if (f.index == 400) CHECK(s.position.x == Approx(715.0 + 100.0).epsilon(kStraightRel));
    if (f.index == 700) CHECK(s.position.x == Approx(3010.0).epsilon(1e-6));
  }
  CHECK(cut_frames == std::vector<std::int64_t>{250, 400, 600});
  // On the cut frame the velocity is that of the new motion.
  CHECK(path.state(2.5, 2.49).velocity.x == Approx(10.0));
}

TEST_CASE("periodic cuts jump ahead or cycle through targets", "[camera]") {
  SECTION("jump ahead every 10 s") {
    const auto r = parse_camera_path(R"({"points": [[0,0,0],[5000,0,0]], "speed_mps": 10,
        "periodic_cut": {"every_s": 10, "jump_ahead_m": 500}})");
    const CameraPath path(r, flat());
    int cuts = 0;
    double prev = 0.0;
    for (int k = 0; k < 35 * 30; ++k) {  // 30 fps for 35 s
      const double t = k / 30.0;
      cuts += path.state(t, prev).cut ? 1 : 0;
      prev = t;
    }
    CHECK(cuts == 3);
    // After cuts at 10, 20, 30 s: 350 m travelled plus 3 x 500 m.
    CHECK(path.state(35.0, 35.0).position.x == Approx(1850.0).epsilon(kStraightRel));
  }
  SECTION("targets cycle") {
    const auto r = parse_camera_path(R"({"points": [[0,0,0],[5000,0,0]], "speed_mps": 10,
        "periodic_cut": {"every_s": 5, "first_s": 1, "targets_m": [1000, 2000]}})");
    const CameraPath path(r, flat());
    CHECK(path.state(1.0, 0.99).cut);
    CHECK(path.state(1.0, 1.0).position.x == Approx(1000.0).epsilon(kStraightRel));
    CHECK(path.state(6.5, 6.5).position.x == Approx(2005.0).epsilon(kStraightRel));
    CHECK(path.state(11.0, 11.0).position.x == Approx(1000.0).epsilon(kStraightRel));
  }
}

TEST_CASE("looping: an open course cuts on the wrap, a closed one does not", "[camera]") {
  auto open = straight({0, 0, 0}, {100, 0, 0}, 10.0);
  open.at_end = CameraPathRecord::AtEnd::loop;
  const CameraPath p(open, flat());
  CHECK(p.state(10.05, 9.95).cut);
  CHECK(p.state(10.05, 9.95).position.x == Approx(0.5).epsilon(1e-9));
  CHECK_FALSE(p.state(12.0, 11.0).cut);
  CameraPathRecord ring;
  ring.points = {{0, 0, 0}, {100, 0, 0}, {100, 100, 0}, {0, 100, 0}, {0, 0, 0}};
  ring.speed.speed_mps = 10.0;
  ring.at_end = CameraPathRecord::AtEnd::loop;
  const CameraPath q(ring, flat());
  const double lap = q.course_length() / 10.0;
  CHECK_FALSE(q.state(lap + 0.01, lap - 0.01).cut);
}

TEST_CASE("keyframe z above ground adds the ground height at the points", "[camera]") {
  TerrainQueries slope;
  slope.ground_height = [](double x, double) { return 0.1 * x; };
  const auto r = parse_camera_path(R"({"points": [[0,0,20],[1000,0,20]], "z_mode": "above_ground",
      "speed_mps": 80})");
  const CameraState s = CameraPath(r, slope).state(5.0, 5.0);
  // The straight segment from (0,0,20) to (1000,0,120): 400 m of arc is at x = 400 / 1.005.
  CHECK(s.position.z - 0.1 * s.position.x == Approx(20.0).epsilon(kStraightRel));
}

TEST_CASE("camera path JSON errors name the path", "[camera]") {
  CHECK_THROWS_WITH(
      parse_camera_path(R"({"points": [[0,0,0],[1,0,0]], "speed_mps": 1, "sped": 2})"),
      Catch::Contains("/camera/sped"));
  CHECK_THROWS_WITH(parse_camera_path(R"({"points": [[0,0,0],[1,0]], "speed_mps": 1})"),
                    Catch::Contains("/camera/points/1"));
  CHECK_THROWS_WITH(parse_camera_path(R"({"points": [[0,0,0],[1,0,0]]})"),
                    Catch::Contains("exactly one of speed_mps or speed_profile"));
  CHECK_THROWS_WITH(
      parse_camera_path(R"({"points": [[0,0,0],[1,0,0]], "speed_mps": 1, "lane_offset_m": 2})"),
      Catch::Contains("/camera/lane_offset_m"));
  CHECK_THROWS_WITH(parse_camera_path(R"({"type": "road", "speed_mps": 1, "direction": 0})"),
                    Catch::Contains("+1 or -1"));
  CHECK_THROWS_WITH(parse_camera_path(R"({"points": [[0,0,0],[1,0,0]], "speed_mps": 1,
      "cuts": [{"time_s": 2, "jump_ahead_m": 1}, {"time_s": 1, "jump_ahead_m": 1}]})"),
                    Catch::Contains("/camera/cuts/1/time_s"));
  CHECK_THROWS_WITH(parse_camera_path(R"({"points": [[0,0,0],[1,0,0]], "speed_profile": [
      {"arc_length_m": 0, "speed_mps": 0}]})"),
                    Catch::Contains("/camera/speed_profile/0/speed_mps"));
}
