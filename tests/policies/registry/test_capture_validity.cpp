// No planner captures inside a solid: every capture point any registered planner asks for, in
// a bake or at run time, stands on or above the terrain and the canopy (a cube map rendered
// inside a hill or a crown sees its backfaces, and its light would be attributed to a point
// the player never stands at: the leak the thesis warns of, L318).
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "policies/registry/registry.h"
#include "sim/run/reference_track.h"
#include "sim/run/simulator.h"
#include "sim/scenario/scenario.h"
#include "sim/world/world.h"
#include "tests/support/scenario_fixtures.h"

using namespace ambisim;

namespace {

// Forwards everything to the planner under test and keeps every capture point it asks for.
class RecordingPlanner final : public Planner {
 public:
  explicit RecordingPlanner(Planner& inner) : inner_(inner) {}
  std::vector<glm::dvec3> points;

  std::string name() const override { return inner_.name(); }
  nlohmann::json params() const override { return inner_.params(); }
  std::vector<CaptureRequest> preload(const FrameContext& ctx) override {
    return keep(inner_.preload(ctx));
  }
  std::vector<CaptureRequest> plan(const FrameContext& ctx) override {
    return keep(inner_.plan(ctx));
  }
  void started(std::uint64_t tag) override { inner_.started(tag); }
  void refused(std::uint64_t tag) override { inner_.refused(tag); }
  void deliver(const FinishedProbe& probe) override { inner_.deliver(probe); }
  void update(const FrameContext& ctx) override { inner_.update(ctx); }
  LookupResult lookup(const glm::dvec3& p) const override { return inner_.lookup(p); }
  PlannerStats stats() const override { return inner_.stats(); }
  void set_receivers(const std::vector<ReceiverView>& r) override { inner_.set_receivers(r); }
  bool ignores_budget() const override { return inner_.ignores_budget(); }

 private:
  std::vector<CaptureRequest> keep(std::vector<CaptureRequest> requests) {
    for (const auto& r : requests) points.push_back(r.position);
    return requests;
  }
  Planner& inner_;
};

}  // namespace

TEST_CASE("no planner captures inside terrain or canopy", "[contract][solids][heavy]") {
  // Every shipped scenario's first 3 s: the forest edge flight (canopy), the cliffs, the
  // motorway in hills, the imported level.
  const auto scenarios = test::short_scenarios(3.0);
  for (const auto& sc : scenarios) {
    const World& world = test::world_for(sc);
    const auto reference = compute_reference_track(sc, world);
    for (const auto& info : planner_catalogue()) {
      INFO(info.name << " on " << sc.name);
      auto inner = test::make_test_planner(info.name);
      RecordingPlanner planner(*inner);
      simulate(sc, world, *reference, planner);
      std::int64_t inside = 0;
      double worst_m = 0.0;
      for (const glm::dvec3& p : planner.points) {
        const double below = world.surface_height(p.x, p.y) - p.z;
        if (below > 1e-6) {
          ++inside;
          worst_m = std::max(worst_m, below);
        }
      }
      INFO(inside << " of " << planner.points.size() << " capture points inside a solid, the "
                  << "deepest " << worst_m << " m");
      CHECK(inside == 0);
    }
  }
}
