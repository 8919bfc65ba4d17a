// `per_object` (thesis 7.5.1) driven by hand and by a small fake frame loop with the
// simulator's budget rule (startable = faces this frame - faces still owed): the 300 fps
// argument, re-capture rules, priority, lookups, and forgetting despawned objects.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "policies/baselines/per_object.h"
#include "policies/core/default_ambient.h"
#include "policies/registry/registry.h"
#include "sim/planner.h"
#include "sim/sh/sh9.h"

using namespace ambisim;

namespace {

using Receivers = std::vector<Planner::ReceiverView>;

PerObjectPlanner make_per_object(const std::vector<std::string>& sets) {
  return PerObjectPlanner(planner_params_from_cli("per_object", sets));
}

Sh9Rgb grey_sh(float v) {
  Sh9Rgb s;
  s.c[0] = Rgb(v, v, v);
  return s;
}

FrameContext frame_at(double time, double dt, int startable) {
  FrameContext c;
  c.frame = static_cast<std::int64_t>(std::llround(time / dt));
  c.time = time;
  c.dt = dt;
  c.startable_captures = startable;
  return c;
}

// The simulator's frame loop in miniature, 1 face per frame, 6 faces per capture, oldest
// capture rendered first; `spawn_per_s` static receivers appear on a line.
struct FakeLoop {
  struct Flight {
    CaptureRequest req;
    double requested = 0.0;
    int faces = 0;
  };
  FakeLoop(double frames_per_s, double spawns_per_s)
      : fps(frames_per_s), spawn_per_s(spawns_per_s) {}
  PerObjectPlanner planner = make_per_object({"lifetime_s=1000"});
  double fps;
  double spawn_per_s;
  Receivers receivers;
  std::vector<Flight> flights;
  double spawn_credit = 0.0;
  std::int64_t frame = 0;
  std::int64_t delivered = 0;

  void step() {
    const double dt = 1.0 / fps;
    const double t = static_cast<double>(frame++) * dt;
    spawn_credit += spawn_per_s * dt;
    while (spawn_credit >= 1.0 - 1e-9) {
      spawn_credit -= 1.0;
      const auto id = static_cast<std::uint64_t>(receivers.size());
      receivers.push_back({id, {static_cast<double>(id) * 3.0, 0.0, 1.0}, {0.0, 0.0, 0.0}});
    }
    int owed = 0;
    for (const auto& f : flights) owed += 6 - f.faces;
    const int startable = std::max(0, 1 - owed);
    planner.set_receivers(receivers);
    int started = 0;
    for (const auto& r : planner.plan(frame_at(t, dt, startable))) {
      if (started++ < startable) {
        planner.started(r.tag);
        flights.push_back({r, t, 0});
      } else {
        planner.refused(r.tag);
      }
    }
    if (!flights.empty()) ++flights.front().faces;  // the frame's one face
    planner.update(frame_at(t, dt, startable));
    if (!flights.empty() && flights.front().faces == 6) {
      const Flight f = flights.front();
      flights.erase(flights.begin());
      planner.deliver({f.req.tag, f.req.position, grey_sh(1.0f), f.requested, t});
      ++delivered;
    }
  }
  void run_for(double seconds) {
    const auto n = static_cast<std::int64_t>(std::llround(seconds * fps));
    for (std::int64_t i = 0; i < n; ++i) step();
  }
};

}  // namespace

TEST_CASE("per_object: 50 spawns/s outrun 1 face/frame at 60 fps, 300 fps keeps up",
          "[baselines]") {
  // 60 fps, 1 face per frame: 10 captures/s against 50 new objects/s.
  FakeLoop slow(60.0, 50.0);
  slow.run_for(2.0);
  const std::size_t at2 = slow.planner.backlog();
  slow.run_for(2.0);
  const std::size_t at4 = slow.planner.backlog();
  // ~40 more waiting each second: 80 at 2 s, 160 at 4 s (give or take the one in flight).
  CHECK(at2 >= 75);
  CHECK(at2 <= 85);
  CHECK(at4 >= 155);
  CHECK(at4 <= 165);
  CHECK(slow.delivered <= 40);

  // The thesis' 300 fps (6x the frame budget): 50 captures/s, enough for 50 objects/s.
  FakeLoop fast(300.0, 50.0);
  std::size_t worst = 0;
  for (int i = 0; i < 4 * 300; ++i) {
    fast.step();
    worst = std::max(worst, fast.planner.backlog());
  }
  CHECK(worst <= 2);
  CHECK(fast.delivered >= 4 * 50 - 2);
  CHECK(fast.planner.tracked() == 200);
}

TEST_CASE("per_object: own capture at a receiver, nearest receiver's capture elsewhere",
          "[baselines]") {
  auto p = make_per_object({});
  // Before any capture: the default ambient, fell back.
  LookupResult none = p.lookup({0, 0, 0});
  CHECK(none.fell_back);
  CHECK(none.sh == default_ambient_sh());
  CHECK(none.contributor_count == 0);
  CHECK(std::isinf(none.spacing_m));

  const glm::dvec3 a{0, 0, 1}, b{20, 0, 1}, c{40, 0, 1};
  p.set_receivers({{1, a, {}}, {2, b, {}}, {3, c, {}}});
  const auto req = p.plan(frame_at(0.0, 0.1, 2));
  REQUIRE(req.size() == 2);  // uncaptured in spawn order; only what may start
  CHECK(req[0].position == a);
  CHECK(req[1].position == b);
  for (const auto& r : req) p.started(r.tag);
  CHECK(p.backlog() == 1);  // c waits
  p.update(frame_at(0.0, 0.1, 0));
  p.deliver({req[0].tag, a, grey_sh(1.0f), 0.0, 0.6});
  p.deliver({req[1].tag, b, grey_sh(2.0f), 0.0, 0.6});

  const LookupResult la = p.lookup(a);
  CHECK(la.sh == grey_sh(1.0f));
  CHECK(la.spacing_m == 0.0);
  CHECK_FALSE(la.fell_back);
  REQUIRE(la.contributor_count == 1);
  CHECK(la.contributors[0].tag == req[0].tag);
  CHECK(la.data_time == 0.0);
  // A demand point 7 m from b gets b's capture, spacing 7.
  const LookupResult d = p.lookup({20, 7, 1});
  CHECK(d.sh == grey_sh(2.0f));
  CHECK(d.spacing_m == Approx(7.0));
  // c has no capture yet: its nearest captured neighbour (b) answers, 20 m away.
  const LookupResult lc = p.lookup(c);
  CHECK(lc.sh == grey_sh(2.0f));
  CHECK(lc.spacing_m == Approx(20.0));
  CHECK(p.stats().live_probes == 2);
}

TEST_CASE(
    "per_object: re-captures after move_m or lifetime_s; uncaptured first, then the most "
    "outdated",
    "[baselines]") {
  auto p = make_per_object({"move_m=5", "lifetime_s=10"});
  const glm::dvec3 a{0, 0, 1}, b{100, 0, 1};
  p.set_receivers({{1, a, {}}, {2, b, {}}});
  auto req = p.plan(frame_at(0.0, 0.1, 5));
  REQUIRE(req.size() == 2);
  for (const auto& r : req) p.started(r.tag);
  p.deliver({req[0].tag, a, grey_sh(1.0f), 0.0, 0.5});
  p.deliver({req[1].tag, b, grey_sh(2.0f), 0.0, 0.5});
  // Nothing due: moved 4.9 m, age 1 s.
  p.set_receivers({{1, a + glm::dvec3(4.9, 0, 0), {}}, {2, b, {}}});
  CHECK(p.plan(frame_at(1.0, 0.1, 5)).empty());
  CHECK(p.backlog() == 0);
  // a moved 5.1 m; a new object 3 spawned: the new one first, then a.
  p.set_receivers({{1, a + glm::dvec3(5.1, 0, 0), {}}, {2, b, {}}, {3, {50, 0, 1}, {}}});
  req = p.plan(frame_at(2.0, 0.1, 5));
  REQUIRE(req.size() == 2);
  CHECK(req[0].position == glm::dvec3(50, 0, 1));
  CHECK(req[1].position == a + glm::dvec3(5.1, 0, 0));
  // The moved receiver's own lookup reports how far it is from its capture.
  CHECK(p.lookup(a + glm::dvec3(5.1, 0, 0)).spacing_m == Approx(5.1));
  // At 10.5 s b is too old (1.05) and a, moved 9 m, more outdated (1.8): a, then b.
  p.set_receivers({{1, a + glm::dvec3(9.0, 0, 0), {}}, {2, b, {}}});
  req = p.plan(frame_at(10.5, 0.1, 5));
  REQUIRE(req.size() == 2);
  CHECK(req[0].position == a + glm::dvec3(9.0, 0, 0));
  CHECK(req[1].position == b);
}

TEST_CASE("per_object: despawned receivers are forgotten with their capture", "[baselines]") {
  auto p = make_per_object({});
  const glm::dvec3 a{0, 0, 1}, b{30, 0, 1};
  p.set_receivers({{1, a, {}}, {2, b, {}}});
  auto req = p.plan(frame_at(0.0, 0.1, 2));
  REQUIRE(req.size() == 2);
  for (const auto& r : req) p.started(r.tag);
  p.deliver({req[0].tag, a, grey_sh(1.0f), 0.0, 0.5});
  const std::int64_t bytes_two = p.stats().bytes;
  CHECK(p.stats().live_probes == 1);

  // Both despawn except b, whose capture is still being rendered; then a new object appears.
  p.set_receivers({{2, b, {}}});
  CHECK(p.tracked() == 1);
  CHECK(p.stats().live_probes == 0);
  CHECK(p.stats().bytes < bytes_two);
  CHECK(p.lookup(a).fell_back);  // a's capture is gone

  p.set_receivers({{3, {60, 0, 1}, {}}});
  p.deliver({req[1].tag, b, grey_sh(2.0f), 0.0, 0.5});  // b is gone: dropped
  CHECK(p.stats().live_probes == 0);
  CHECK(p.lookup(b).fell_back);
  CHECK(p.backlog() == 1);
  std::vector<ProbeNodeView> nodes;
  p.describe_nodes(nodes);
  CHECK(nodes.empty());
}
