// Receivers: spawn counts at the thesis' rates, traffic kinematics, determinism by seed.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <map>

#include <glm/geometric.hpp>

#include "sim/scenario/receivers.h"

using namespace ambisim;

namespace {

// Straight roads and paths are exact up to float sums (camera path: 3e-15 relative).
constexpr double kStraightRel = 1e-9;

TerrainQueries sloped() {
  TerrainQueries t;
  t.ground_height = [](double x, double) { return 0.1 * x; };
  return t;
}

CameraPath flight(double speed) {
  CameraPathRecord r;
  r.points = {{0, 0, 50}, {5000, 0, 50}};
  r.speed.speed_mps = speed;
  return CameraPath(r, sloped());
}

LodPropsRecord props(glm::dvec3 trigger, double lod_distance) {
  LodPropsRecord l;
  l.trigger = trigger;
  l.lod_distance_m = lod_distance;
  return l;
}

// Runs `set` over frames k / fps for k = 0..frames, returning the last camera state.
CameraState run(ReceiverSet& set, const CameraPath& path, double fps, int frames) {
  CameraState cam;
  double prev = 0.0;
  for (int k = 0; k <= frames; ++k) {
    const double t = k / fps;
    cam = path.state(t, prev);
    set.update(t, cam);
    prev = t;
  }
  return cam;
}

std::int64_t spawned(const ReceiverSet& s, ReceiverKind k) {
  return s.counters().spawned[static_cast<int>(k)];
}

}  // namespace

TEST_CASE("lod props appear at 50 per second in a band ahead of the camera", "[receivers]") {
  ReceiversRecord rec;
  rec.lod_props = props({1e5, 0, 0}, 1e6);  // inside from the first frame
  ReceiverSet set(rec, sloped());
  const CameraPath path = flight(80.0);
  const LodPropsRecord& L = *rec.lod_props;
  double prev = 0.0;
  for (int k = 0; k <= 1000; ++k) {  // 100 fps, t = 0 .. 10 s
    const double t = k / 100.0;
    const CameraState cam = path.state(t, prev);
    set.update(t, cam);
    prev = t;
    for (const Receiver& r : set.live()) {
      if (r.kind != ReceiverKind::lod_prop || r.spawn_time != t) continue;
      const glm::dvec3 d = r.position - cam.position;
      CHECK(d.x >= L.band_near_m);
      CHECK(d.x <= L.band_far_m);
      CHECK(std::abs(d.y) <= L.band_half_width_m);
      const double above = r.position.z - 0.1 * r.position.x;
      CHECK(above >= L.min_height_m - 1e-12);
      CHECK(above <= L.max_height_m + 1e-12);
      CHECK(glm::length(r.velocity) == 0.0);
    }
  }
  // Deterministic rate: floor(active seconds x rate) = floor(10 x 50), exactly.
  CHECK(set.lod_emitted() == 500);
  CHECK(spawned(set, ReceiverKind::lod_prop) == 500);
  // Props fall behind an 80 m/s camera: the live count stays near
  // 50/s x (150 m + 10 m margin) / 80 m/s = 100, far below the cap.
  CHECK(set.counters().despawned[static_cast<int>(ReceiverKind::lod_prop)] > 300);
  for (const Receiver& r : set.live()) {
    if (r.kind == ReceiverKind::lod_prop)
      CHECK(r.position.x - path.state(10, 10).position.x >= -10);
  }
}

TEST_CASE("lod props spawn only while the camera is within the lod distance", "[receivers]") {
  // Inside for x in [1800.4, 2200.4], i.e. t in [22.505, 27.505] at 80 m/s. At 100 fps the
  // first inside frame is 22.51 and the last 27.50: 4.99 s of spawn clock -> floor(249.5).
  ReceiversRecord rec;
  rec.lod_props = props({2000.4, 0, 0}, 200.0);
  ReceiverSet set(rec, sloped());
  run(set, flight(80.0), 100.0, 3000);
  CHECK(set.lod_emitted() == 249);
}

TEST_CASE("lod props honour lifetime and the live cap", "[receivers]") {
  SECTION("lifetime: a standing camera keeps the last second's props") {
    ReceiversRecord rec;
    rec.lod_props = props({0, 0, 0}, 1e6);
    rec.lod_props->lifetime_s = 1.0;
    ReceiverSet set(rec, sloped());
    run(set, flight(0.0), 100.0, 1000);
    // Spawned in (9 s, 10 s]: 500 - floor(9 x 50).
    CHECK(std::count_if(set.live().begin(), set.live().end(),
                        [](const Receiver& r) { return r.kind == ReceiverKind::lod_prop; }) == 50);
  }
  SECTION("cap") {
    ReceiversRecord rec;
    rec.lod_props = props({0, 0, 0}, 1e6);
    rec.lod_props->max_live = 10;
    ReceiverSet set(rec, sloped());
    run(set, flight(0.0), 100.0, 1000);
    CHECK(spawned(set, ReceiverKind::lod_prop) == 10);
    CHECK(set.counters().suppressed[static_cast<int>(ReceiverKind::lod_prop)] == 490);
  }
}

TEST_CASE("the camera object rides ahead of the camera on the ground", "[receivers]") {
  ReceiversRecord rec;  // camera object on by default: 8 m ahead, 1 m above ground
  ReceiverSet set(rec, sloped());
  const CameraState cam = run(set, flight(80.0), 50.0, 100);
  REQUIRE(set.live().size() == 1);
  const Receiver& r = set.live().front();
  CHECK(r.id == 0);
  CHECK(r.kind == ReceiverKind::camera_object);
  CHECK(r.position.x == Approx(cam.position.x + 8.0).epsilon(kStraightRel));
  CHECK(r.position.z == Approx(0.1 * r.position.x + 1.0).epsilon(kStraightRel));
  CHECK(r.velocity.x == Approx(80.0).epsilon(kStraightRel));
  CHECK(r.velocity.z == Approx(8.0).epsilon(1e-6));  // slope 0.1 x 80 m/s
}

TEST_CASE("a camera object that follows the camera flies with it, never into the ground",
          "[receivers]") {
  ReceiversRecord rec;
  rec.camera_object.follow = CameraObjectRecord::Follow::camera;
  SECTION("2 m below a level flight at 50 m") {
    rec.camera_object.height_m = -2.0;
    ReceiverSet set(rec, sloped());
    const CameraState cam = run(set, flight(80.0), 50.0, 100);
    const Receiver& r = set.live().front();
    CHECK(r.position.x == Approx(cam.position.x + 8.0).epsilon(kStraightRel));
    CHECK(r.position.z == Approx(cam.position.z - 2.0).epsilon(1e-12));
    CHECK(r.velocity.z == Approx(cam.velocity.z).margin(1e-9));
  }
  SECTION("an offset below the surface is held 0.5 m above it") {
    rec.camera_object.height_m = -45.0;  // camera at 50 m, ground 0.1 x ~ 17 m
    ReceiverSet set(rec, sloped());
    run(set, flight(80.0), 50.0, 100);
    const Receiver& r = set.live().front();
    CHECK(r.position.z == Approx(0.1 * r.position.x + CameraObjectRecord::kMinClearance));
    CHECK(r.velocity.z == 0.0);
  }
}

TEST_CASE("traffic drives both carriageways at 30 m/s, oncoming the other way", "[receivers]") {
  const Spline3 road({{0, 0, 0}, {10000, 0, 0}});
  TerrainQueries t = sloped();
  t.road = &road;
  t.road_width = 14.0;  // lanes 3.5 m either side of the centre line
  CameraPathRecord cr;
  cr.type = CameraPathRecord::Type::road;
  cr.start_arc_length_m = 1000.0;
  cr.speed.speed_mps = 30.0;
  const CameraPath path(cr, t);
  ReceiversRecord rec;
  rec.camera_object.enabled = false;
  rec.traffic = TrafficRecord{};
  ReceiverSet set(rec, t);
  std::map<std::uint64_t, glm::dvec3> last;
  int same = 0, oncoming = 0;
  double prev = 0.0;
  for (int k = 0; k <= 200; ++k) {  // 10 fps for 20 s
    const double time = k / 10.0;
    const CameraState cam = path.state(time, prev);
    set.update(time, cam);
    for (const Receiver& r : set.live()) {
      REQUIRE(r.kind == ReceiverKind::traffic);
      CHECK(glm::length(r.velocity) == Approx(30.0).epsilon(kStraightRel));
      CHECK(r.position.z == Approx(1.0).epsilon(kStraightRel));
      if (r.lane_direction > 0) {
        CHECK(r.position.y == Approx(-3.5).epsilon(kStraightRel));
        CHECK(glm::dot(r.velocity, cam.velocity) > 0.0);
      } else {
        CHECK(r.position.y == Approx(3.5).epsilon(kStraightRel));
        CHECK(glm::dot(r.velocity, cam.velocity) < 0.0);
      }
      // Inside the window: 200 m behind to 800 m ahead of the camera.
      CHECK(r.position.x >= cam.position.x - 200.0 - 1e-9);
      CHECK(r.position.x <= cam.position.x + 800.0 + 1e-9);
      if (auto it = last.find(r.id); it != last.end()) {
        CHECK(r.position.x - it->second.x == Approx(r.lane_direction * 3.0).epsilon(1e-6));
      }
      last[r.id] = r.position;
      (r.lane_direction > 0 ? same : oncoming) += r.spawn_time == time ? 1 : 0;
    }
    prev = time;
  }
  CHECK(set.traffic_emitted() == 200);  // floor(20 s x 10 / s)
  CHECK(spawned(set, ReceiverKind::traffic) == 200);
  CHECK(same + oncoming == 200);
  CHECK(same > 50);  // a fair coin over 200 draws: 100 +- 7 (1 sigma)
  CHECK(oncoming > 50);
  // Oncoming cars close at 60 m/s and leave the window: some must have gone.
  CHECK(set.counters().despawned[static_cast<int>(ReceiverKind::traffic)] > 0);
}

TEST_CASE("the same seed gives the same receivers, another seed others", "[receivers]") {
  const Spline3 road({{0, 0, 0}, {10000, 0, 0}});
  TerrainQueries t = sloped();
  t.road = &road;
  t.road_width = 14.0;
  ReceiversRecord rec;
  rec.seed = 42;
  rec.lod_props = props({0, 0, 0}, 1e6);
  rec.traffic = TrafficRecord{};
  const CameraPath path = flight(30.0);
  ReceiverSet a(rec, t), b(rec, t);
  rec.seed = 43;
  ReceiverSet c(rec, t);
  run(a, path, 60.0, 300);
  run(b, path, 60.0, 300);
  run(c, path, 60.0, 300);
  REQUIRE(a.live().size() == b.live().size());
  bool differs = false;
  for (std::size_t i = 0; i < a.live().size(); ++i) {
    CHECK(a.live()[i].id == b.live()[i].id);
    CHECK(a.live()[i].position == b.live()[i].position);  // bitwise
    if (i < c.live().size() && c.live()[i].position != a.live()[i].position) differs = true;
  }
  CHECK(differs);
  // Ids are unique and increasing.
  for (std::size_t i = 1; i < a.live().size(); ++i) CHECK(a.live()[i].id > a.live()[i - 1].id);
}

TEST_CASE("receivers JSON errors name the path", "[receivers]") {
  auto parse = [](const char* text) {
    const auto j = nlohmann::json::parse(text);
    ObjectReader r(j, "t.json", "/receivers");
    return parse_receivers(r);
  };
  const auto ok = parse(R"({"seed": 7, "lod_props": {"trigger": [1, 2, 3]}, "traffic": {}})");
  CHECK(ok.seed == 7);
  CHECK(ok.lod_props->rate_per_s == 50.0);
  CHECK(ok.traffic->speed_mps == 30.0);
  CHECK(ok.traffic->rate_per_s == 10.0);
  CHECK_THROWS_WITH(parse(R"({"lod_props": {}})"), Catch::Contains("/receivers/lod_props/trigger"));
  CHECK_THROWS_WITH(parse(R"({"traffic": {"sped_mps": 3}})"),
                    Catch::Contains("/receivers/traffic/sped_mps"));
  CHECK_THROWS_WITH(parse(R"({"lod_props": {"trigger": [0,0,0], "band_near_m": 50,
      "band_far_m": 10}})"),
                    Catch::Contains("band_far_m"));
}

TEST_CASE("a crowd stands in its disc, and its walkers mill at walking speed", "[receivers]") {
  ReceiversRecord rec;
  rec.camera_object.enabled = false;
  CrowdRecord c;
  c.centre = {100.0, -50.0, 0.0};
  c.count = 2000;
  c.radius_m = 110.0;
  rec.crowd = c;
  ReceiverSet set(rec, sloped());
  const CameraPath path = flight(0.0);
  // Displacement over one frame gives the speed (compared with the reported velocity).
  std::map<std::uint64_t, glm::dvec3> before;
  double speed_sum = 0.0, moving = 0.0, still = 0.0, worst_velocity_error = 0.0;
  const double dt = 1.0 / 60.0;
  for (int k = 0; k <= 600; ++k) {
    const double t = k * dt;
    set.update(t, path.state(t, t > 0 ? t - dt : 0.0));
    REQUIRE(set.live().size() == 2000);
    for (const Receiver& r : set.live()) {
      REQUIRE(r.kind == ReceiverKind::crowd);
      // On the ground (sloped: z = 0.1 x), people 1 m up, props 0.5-1.5 m.
      const double above = r.position.z - 0.1 * r.position.x;
      CHECK(above >= 0.5 - 1e-9);
      CHECK(above <= 1.5 + 1e-9);
      // Home in the disc, wandering at most wander_m (8 m) per axis from it.
      CHECK(glm::length(glm::dvec2(r.position.x - 100.0, r.position.y + 50.0)) <=
            110.0 + 8.0 * std::sqrt(2.0) + 1e-9);
      if (k > 0) {
        const glm::dvec3 step = r.position - before[r.id];
        const double v = glm::length(glm::dvec2(step.x, step.y)) / dt;
        if (glm::length(r.velocity) > 0.0) {
          speed_sum += v;
          moving += 1.0;
          worst_velocity_error =
              std::max(worst_velocity_error, glm::length(glm::dvec2(step.x, step.y) / dt -
                                                         glm::dvec2(r.velocity.x, r.velocity.y)));
        } else {
          CHECK(v == 0.0);
          still += 1.0;
        }
      }
      before[r.id] = r.position;
    }
  }
  // Half walk (walking_share 0.5, 2000 draws: within 4 standard deviations).
  CHECK(moving / (moving + still) == Approx(0.5).margin(0.045));
  // Mean walking speed near 1.4 m/s (the loops' speeds vary around it).
  CHECK(speed_sum / moving == Approx(1.4).epsilon(0.25));
  // The reported velocity is the derivative of the motion (one frame of curvature apart).
  CHECK(worst_velocity_error < 0.05);
  CHECK(spawned(set, ReceiverKind::crowd) == 2000);
  // Deterministic: another set from the same record is identical.
  ReceiverSet again(rec, sloped());
  again.update(0.0, path.state(0.0, 0.0));
  ReceiverSet first(rec, sloped());
  first.update(0.0, path.state(0.0, 0.0));
  CHECK(again.live()[1234].position == first.live()[1234].position);
}
