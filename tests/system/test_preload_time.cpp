// Preload captures in the light of another time (CaptureRequest::time, for bakes at several
// times of day): rendered exactly as a capture in that moment's light, without changing
// anything else in the run; and refused outside preload.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>

#include "policies/core/default_ambient.h"
#include "policies/registry/registry.h"
#include "sim/render/capture.h"
#include "sim/run/run_output.h"
#include "sim/run/simulator.h"
#include "sim/scenario/scenario_motion.h"
#include "sim/sh/sh_projection.h"
#include "sim/world/illumination.h"
#include "sim/world/lighting_model.h"
#include "tests/support/scenario_fixtures.h"

using namespace ambisim;

namespace {

// Preloads the given requests (and asks for `in_plan` every frame), records what arrives.
class PreloadRecorder final : public Planner {
 public:
  explicit PreloadRecorder(std::vector<CaptureRequest> preload,
                           std::vector<CaptureRequest> in_plan = {})
      : preload_(std::move(preload)), in_plan_(std::move(in_plan)) {}
  std::string name() const override { return "preload_recorder"; }
  nlohmann::json params() const override { return nlohmann::json::object(); }
  std::vector<CaptureRequest> preload(const FrameContext& ctx) override {
    duration_s = ctx.run_duration_s;
    return preload_;
  }
  std::vector<CaptureRequest> plan(const FrameContext& /*ctx*/) override { return in_plan_; }
  void started(std::uint64_t /*tag*/) override {}
  void deliver(const FinishedProbe& p) override { delivered.push_back(p); }
  void update(const FrameContext& /*ctx*/) override {}
  LookupResult lookup(const glm::dvec3& /*p*/) const override { return default_ambient_lookup(); }
  PlannerStats stats() const override { return {}; }

  std::vector<FinishedProbe> delivered;
  double duration_s = -1.0;

 private:
  std::vector<CaptureRequest> preload_, in_plan_;
};

// Forwards to `constant` and adds one preload capture in another time's light, which
// `constant` ignores (it keeps the first capture delivered: its own, at frame 0's light).
class ConstantPlusOther final : public Planner {
 public:
  ConstantPlusOther() : inner_(make_planner("constant")) {}
  std::string name() const override { return inner_->name(); }
  nlohmann::json params() const override { return inner_->params(); }
  std::vector<CaptureRequest> preload(const FrameContext& ctx) override {
    std::vector<CaptureRequest> r = inner_->preload(ctx);
    CaptureRequest other;
    other.position = ctx.camera_position + glm::dvec3(5.0, 0.0, 0.0);
    other.tag = 999;
    other.time = 0.7;
    r.insert(r.begin(), other);  // before the planner's own: the simulator sorts by time
    return r;
  }
  std::vector<CaptureRequest> plan(const FrameContext& ctx) override { return inner_->plan(ctx); }
  void started(std::uint64_t tag) override { inner_->started(tag); }
  void refused(std::uint64_t tag) override { inner_->refused(tag); }
  void deliver(const FinishedProbe& p) override { inner_->deliver(p); }
  void update(const FrameContext& ctx) override { inner_->update(ctx); }
  LookupResult lookup(const glm::dvec3& p) const override { return inner_->lookup(p); }
  PlannerStats stats() const override { return inner_->stats(); }

 private:
  std::unique_ptr<Planner> inner_;
};

const Scenario& sunset() {
  static const std::vector<Scenario> all = test::short_scenarios(1.0);
  const auto it = std::find_if(all.begin(), all.end(),
                               [](const Scenario& s) { return s.name == "sunset_drive"; });
  REQUIRE(it != all.end());
  return *it;
}

}  // namespace

TEST_CASE("a preload capture with a time is rendered in that time's light", "[preload]") {
  const Scenario& sc = sunset();
  const World& world = test::world_for(sc);
  const glm::dvec3 at = world.road().empty() ? glm::dvec3(0.0, 0.0, 50.0)
                                             : world.road().at(400.0) + glm::dvec3(0, 0, 2);
  std::vector<CaptureRequest> req(3);
  req[0] = {at, 1, false, 0.8};
  req[1] = {at, 2, false, -1.0};  // frame 0's light
  req[2] = {at, 3, false, 0.4};
  PreloadRecorder planner(req);
  const RunResult r = simulate_without_reference(sc, world, planner);
  CHECK(planner.duration_s == Approx(1.0));
  CHECK(r.summary.bake.captures == 3);
  // Delivered in time order, each exactly as a capture in its own moment's light.
  REQUIRE(planner.delivered.size() == 3);
  CHECK(planner.delivered[0].tag == 2);
  CHECK(planner.delivered[1].tag == 3);
  CHECK(planner.delivered[2].tag == 1);
  const int face = sc.budget.face_size;
  for (const auto& [tag, t] : {std::pair<std::uint64_t, double>{1, 0.8}, {2, 0.0}, {3, 0.4}}) {
    INFO("tag " << tag << " at t = " << t);
    LightingModel lighting(world);
    const CubeMap cube = capture(Illumination(world, lighting.state_at(t)), at, face);
    const Sh9Rgb expected = projector_for(face).project(cube);
    const auto got = std::find_if(planner.delivered.begin(), planner.delivered.end(),
                                  [&](const FinishedProbe& p) { return p.tag == tag; });
    CHECK(got->sh == expected);
    CHECK(got->requested_time == 0.0);
  }
  // The sun sets: the three are different light.
  CHECK_FALSE(planner.delivered[0].sh == planner.delivered[2].sh);
}

TEST_CASE("preload captures at other times leave the run itself unchanged", "[preload]") {
  const Scenario& sc = sunset();
  const World& world = test::world_for(sc);
  const auto reference = compute_reference_track(sc, world);
  auto plain = make_planner("constant");
  ConstantPlusOther with_other;
  const RunResult a = simulate(sc, world, *reference, *plain);
  const RunResult b = simulate(sc, world, *reference, with_other);
  CHECK(b.summary.bake.captures == a.summary.bake.captures + 1);
  auto ja = result_json(sc, {"constant", plain->params()}, a);
  auto jb = result_json(sc, {"constant", with_other.params()}, b);
  ja["summary"].erase("bake");
  jb["summary"].erase("bake");
  CHECK(ja.dump() == jb.dump());
  CHECK(frames_csv(a) == frames_csv(b));
}

TEST_CASE("a capture time outside preload is refused", "[preload]") {
  const Scenario& sc = sunset();
  const World& world = test::world_for(sc);
  CaptureRequest late;
  late.tag = 1;
  late.time = 0.5;
  PreloadRecorder planner({}, {late});
  CHECK_THROWS_AS(simulate_without_reference(sc, world, planner), std::logic_error);
}

TEST_CASE("a preload capture may ask for its own face size, a run capture may not", "[preload]") {
  const Scenario& sc = sunset();
  const World& world = test::world_for(sc);
  const glm::dvec3 at = world.road().empty() ? glm::dvec3(0.0, 0.0, 50.0)
                                             : world.road().at(400.0) + glm::dvec3(0, 0, 2);
  CaptureRequest fine;
  fine.position = at;
  fine.tag = 1;
  fine.face_size = 24;
  PreloadRecorder planner({fine});
  const RunResult r = simulate_without_reference(sc, world, planner);
  CHECK(r.summary.bake.captures == 1);
  REQUIRE(planner.delivered.size() == 1);
  LightingModel lighting(world);
  const CubeMap cube = capture(Illumination(world, lighting.state_at(0.0)), at, 24);
  CHECK(planner.delivered[0].sh == projector_for(24).project(cube));
  const CubeMap coarse = capture(Illumination(world, lighting.state_at(0.0)), at, 16);
  CHECK_FALSE(planner.delivered[0].sh == projector_for(16).project(coarse));

  CaptureRequest late;
  late.tag = 2;
  late.face_size = 24;
  PreloadRecorder refused({}, {late});
  CHECK_THROWS_AS(simulate_without_reference(sc, world, refused), std::logic_error);
}

TEST_CASE("object_cells holds every square a receiver visits, and no other", "[preload]") {
  // Slow reference: every receiver at every frame, its square; against the function's list.
  const Scenario& sc = sunset();
  const World& world = test::world_for(sc);
  const double cell = 10.0;
  const auto cells = object_cells(sc, world, cell);
  std::set<std::pair<long, long>> expected;
  ScenarioMotion motion(sc, world);
  while (motion.next()) {
    for (const auto& rc : motion.receivers()) {
      expected.insert({static_cast<long>(std::floor(rc.position.x / cell)),
                       static_cast<long>(std::floor(rc.position.y / cell))});
    }
  }
  REQUIRE(cells.size() == expected.size());
  auto it = expected.begin();
  for (const auto& c : cells) {
    CHECK(c.x == Approx((static_cast<double>(it->first) + 0.5) * cell));
    CHECK(c.y == Approx((static_cast<double>(it->second) + 0.5) * cell));
    ++it;
  }
  // Traffic on both carriageways, hundreds of metres beyond the camera's short route.
  const glm::dvec3 start = camera_route(motion, 10.0).front();
  double farthest = 0.0;
  for (const auto& c : cells)
    farthest = std::max(farthest, std::hypot(c.x - start.x, c.y - start.y));
  CHECK(farthest > 200.0);
}
