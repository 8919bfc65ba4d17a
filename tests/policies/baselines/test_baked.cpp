// The baked baselines (`baked`, `baked_tod`): the lattice's spacing rule, trilinear exactness,
// the virtual offset, no captures at run time, and the time-of-day blend, on synthetic worlds
// (flat ground, a straight route) and on the shipped ones.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

#include <glm/geometric.hpp>

#include "policies/baselines/baked.h"
#include "policies/core/default_ambient.h"
#include "policies/registry/registry.h"
#include "sim/render/capture.h"
#include "sim/run/simulator.h"
#include "sim/scenario/scenario_motion.h"
#include "sim/world/world_queries.h"
#include "tests/support/scenario_fixtures.h"

using namespace ambisim;

namespace {

// Flat ground at `ground_z` and a straight route along +x from 0 to length_m, 1.5 m up.
struct FlatLevel {
  WorldQueries world;
  explicit FlatLevel(double ground_z, double length_m = 100.0) {
    world.ground_height = [ground_z](double, double) { return ground_z; };
    world.surface_height = world.ground_height;
    for (double x = 0.0; x <= length_m + 1e-9; x += 10.0) {
      world.route.push_back({x, 0.0, ground_z + 1.5});
    }
  }
  FrameContext context(double time = 0.0, double duration_s = 0.0) const {
    FrameContext c;
    c.time = time;
    c.dt = 1.0 / 60.0;
    c.world = &world;
    c.run_duration_s = duration_s;
    c.camera_position = world.route.front();
    return c;
  }
};

std::unique_ptr<BakedPlanner> baked_with(const std::string& name,
                                         const std::vector<std::string>& sets) {
  auto planner = make_planner(name, planner_params_from_cli(name, sets));
  return std::unique_ptr<BakedPlanner>(static_cast<BakedPlanner*>(planner.release()));
}

// A linear field of SH sets: coefficient k, channel ch = a + b . p (all 27 different).
Sh9Rgb linear_field(const glm::dvec3& p) {
  Sh9Rgb s;
  for (int k = 0; k < kShCount; ++k) {
    for (int ch = 0; ch < 3; ++ch) {
      const double a = 1.0 + 0.1 * k + 0.03 * ch;
      const glm::dvec3 b(0.01 * (k + 1), -0.02 * (ch + 1), 0.05 + 0.01 * k);
      s.c[k][ch] = static_cast<float>(a + glm::dot(b, p));
    }
  }
  return s;
}

Sh9Rgb uniform_sh(float radiance) {
  Sh9Rgb s;
  s.c[0] = Rgb(radiance * static_cast<float>(4.0 * std::numbers::pi * kShY00));
  return s;
}

double max_coefficient_difference(const Sh9Rgb& a, const Sh9Rgb& b) {
  double m = 0.0;
  for (int k = 0; k < kShCount; ++k) {
    for (int ch = 0; ch < 3; ++ch) m = std::max(m, std::abs(double(a.c[k][ch]) - b.c[k][ch]));
  }
  return m;
}

}  // namespace

TEST_CASE("baked lattice: finest near the surface, 3x coarser per level above it", "[baked]") {
  // Flat ground at 0, spacing 2, band 3: level l covers whole cells up to band 3 x 3^l (the
  // coarsest to top_m), i.e. up to z = 4 (level 0, 2 m), 12 (6 m), 36 (18 m), 108 (54 m).
  const FlatLevel level(0.0);
  auto p = baked_with("baked", {"spacing_m=2", "band_m=3", "levels=4", "top_m=100", "corridor_m=10",
                                "precision=fp32"});
  for (const auto& r : p->preload(level.context())) p->deliver({r.tag, r.position, uniform_sh(1)});
  const BakedLattice& lattice = p->lattice();
  CHECK(lattice.spacing(0) == 2.0);
  CHECK(lattice.spacing(3) == 54.0);
  const std::map<double, double> expected = {{0.5, 2.0},   {3.9, 2.0},   {4.1, 6.0},
                                             {11.9, 6.0},  {12.1, 18.0}, {35.9, 18.0},
                                             {36.1, 54.0}, {107.0, 54.0}};
  for (const auto& [z, spacing] : expected) {
    INFO("z = " << z);
    const LookupResult r = p->lookup({50.3, 1.7, z});
    CHECK_FALSE(r.fell_back);
    CHECK(r.spacing_m == spacing);
  }
  // Above the coarsest level and outside the corridor: the default ambient.
  CHECK(p->lookup({50.3, 1.7, 109.0}).sh == default_ambient_sh());
  CHECK(p->lookup({50.3, 80.0, 1.0}).fell_back);
  // Every level is two cells high here, so each holds far fewer points than the one below it
  // (9x for the same area; the corridor's margin of half a cell's diagonal widens the coarse
  // ones). Level 0: the 2 m columns within 10 + 1.41 m of the route: 12 across, 50 along it
  // plus the rounded ends, each with the lattice planes z = 0, 2, 4.
  const auto& counts = lattice.counts();
  REQUIRE(counts.size() == 4);
  CHECK(counts[0].columns > 50 * 12);
  CHECK(counts[0].columns < 62 * 12);
  CHECK(counts[0].points > 5 * counts[1].points);
  for (std::size_t l = 1; l < counts.size(); ++l) {
    INFO("level " << l << ": " << counts[l].points << " points, below " << counts[l - 1].points);
    CHECK(counts[l].points < counts[l - 1].points);
  }
  // The points at z = 0 sit on the ground: lifted by the clearance (0.1 m), none dropped.
  CHECK(counts[0].dropped == 0);
  CHECK(counts[0].points == 3 * counts[0].moved);

  // A bake budget below level 0's points leaves level 0 out: 1 m up is then served at 6 m.
  const std::int64_t coarse = counts[1].points + counts[2].points + counts[3].points;
  auto small =
      baked_with("baked", {"spacing_m=2", "band_m=3", "levels=4", "top_m=100", "corridor_m=10",
                           "max_captures=" + std::to_string(coarse + 50)});
  for (const auto& r : small->preload(level.context())) {
    small->deliver({r.tag, r.position, uniform_sh(1)});
  }
  CHECK(small->lattice().first_level() == 1);
  CHECK(static_cast<std::int64_t>(small->lattice().size()) == coarse);
  CHECK(small->lookup({50.3, 1.7, 1.0}).spacing_m == 6.0);
}

TEST_CASE("baked corridor follows the route but not across a camera cut", "[baked]") {
  // Two stretches of route 500 m apart (a teleport between them): both are baked, the straight
  // line between them is not.
  FlatLevel level(0.0, 50.0);
  for (double x = 550.0; x <= 600.0; x += 10.0) level.world.route.push_back({x, 0.0, 1.5});
  auto p = baked_with("baked", {});
  for (const auto& r : p->preload(level.context())) p->deliver({r.tag, r.position, uniform_sh(1)});
  CHECK(p->lookup({25.0, 0.0, 1.0}).spacing_m == 2.0);
  CHECK(p->lookup({575.0, 0.0, 1.0}).spacing_m == 2.0);
  CHECK(p->lookup({300.0, 0.0, 1.0}).fell_back);
}

TEST_CASE("baked covers the squares the lit objects visit, as themselves", "[baked]") {
  // A route of 50 m and one object square 300 m down the road (traffic far ahead of the
  // camera): the square is baked at the finest spacing, the road between is not.
  FlatLevel level(0.0, 50.0);
  level.world.object_cells = {{305.0, 5.0, 1.0}};
  level.world.object_cell_m = 10.0;
  auto p = baked_with("baked", {});
  for (const auto& r : p->preload(level.context())) p->deliver({r.tag, r.position, uniform_sh(1)});
  for (const double x : {300.5, 305.0, 309.5}) {
    for (const double y : {0.5, 9.5}) {
      INFO("at " << x << ", " << y);
      CHECK(p->lookup({x, y, 1.0}).spacing_m == 2.0);
    }
  }
  CHECK(p->lookup({200.0, 5.0, 1.0}).fell_back);
  // Its own square plus one lattice cell around it, not a corridor: 30 m off it only the
  // coarse levels that the route's corridor reaches, if any.
  const LookupResult off = p->lookup({305.0, 40.0, 1.0});
  CHECK((off.fell_back || off.spacing_m > 2.0));
}

TEST_CASE("baked lookup is trilinear: exact on a linear SH field", "[baked]") {
  // Ground at -0.5: the lattice planes z = 0, 2, 4 are free, z = -2 is 1.5 m deep (more than
  // half a cell: dropped). Each probe holds the field at its lattice point; inside a cell whose
  // 8 corners exist the lookup reproduces the field exactly (to float rounding).
  const FlatLevel level(-0.5);
  auto p = baked_with("baked", {"spacing_m=2", "band_m=4", "precision=fp32"});
  const auto requests = p->preload(level.context());
  const BakedLattice& lattice = p->lattice();
  REQUIRE(requests.size() == lattice.size());
  for (const auto& r : requests) {
    const BakedLattice::Probe q = lattice.probe(r.tag - 1);
    p->deliver({r.tag, r.position, linear_field(lattice.nominal_position(q))});
  }
  CHECK(lattice.dropped() > 0);
  double worst = 0.0;
  int n = 0;
  for (double x = 3.1; x < 95.0; x += 7.3) {
    for (double y = -9.0; y <= 9.0; y += 2.9) {
      for (double z = 0.05; z < 3.99; z += 0.61) {
        const glm::dvec3 at(x, y, z);
        const LookupResult r = p->lookup(at);
        REQUIRE(r.spacing_m == 2.0);
        REQUIRE(r.contributor_count == 8);
        worst = std::max(worst, max_coefficient_difference(r.sh, linear_field(at)));
        ++n;
      }
    }
  }
  INFO(n << " points, worst difference " << worst);
  CHECK(n > 500);
  CHECK(worst < 2e-5);  // values 1..8: float rounding
  // Between z = -0.5 and 0 the lower corners are dropped: the weights renormalise over the
  // upper four, which hold the field at z = 0 (linear in x, y there).
  const glm::dvec3 low(40.7, 3.3, -0.2);
  const LookupResult r = p->lookup(low);
  CHECK(r.contributor_count == 4);
  CHECK(max_coefficient_difference(r.sh, linear_field({low.x, low.y, 0.0})) < 2e-5);
}

TEST_CASE("baked virtual offset never leaves a probe inside the terrain or canopy", "[baked]") {
  // The motorway (cuttings, embankments) and the forest edge (canopy 15-25 m high with sharp
  // edges), 20 s of each route.
  for (const std::string name : {"motorway", "forest_edge"}) {
    const auto scenarios = test::short_scenarios(20.0);
    const auto sc = std::find_if(scenarios.begin(), scenarios.end(),
                                 [&](const Scenario& s) { return s.name == name; });
    REQUIRE(sc != scenarios.end());
    const World& world = test::world_for(*sc);
    WorldQueries queries = planner_world_queries(world);
    {
      ScenarioMotion motion(*sc, world);
      queries.route = camera_route(motion, 10.0);
    }
    FrameContext ctx;
    ctx.world = &queries;
    ctx.camera_position = queries.route.front();
    auto p = baked_with("baked", {});
    const auto requests = p->preload(ctx);
    const BakedLattice& lattice = p->lattice();
    std::int64_t inside = 0, far = 0, lifted = 0, moved = 0;
    for (std::size_t i = 0; i < lattice.size(); ++i) {
      const BakedLattice::Probe q = lattice.probe(i);
      if (!lattice.is_free(queries.surface_height, q.position)) ++inside;
      const double move = glm::distance(q.position, lattice.nominal_position(q));
      if (move > 0.5 * lattice.spacing(q.level) + 1e-9) ++far;
      if (q.moved) ++moved;
      // What the renderer would do with it: a point inside a column is lifted out.
      if (capture_origin(world, q.position) != q.position) ++lifted;
    }
    INFO(name << ": " << lattice.size() << " probes, " << lattice.moved() << " moved, "
              << lattice.dropped() << " dropped, " << lifted << " inside a column");
    CHECK(requests.size() == lattice.size());
    CHECK(inside == 0);
    CHECK(far == 0);
    CHECK(lifted == 0);
    CHECK(moved == lattice.moved());
    CHECK(lattice.moved() > 0);
    CHECK(lattice.dropped() > 0);
  }
}

TEST_CASE("baked never asks for a capture during the run", "[baked][heavy]") {
  static test::SmallDrive f;
  for (const std::string name : {"baked", "baked_tod"}) {
    INFO(name);
    auto p = make_planner(name);
    const RunResult r = simulate(f.scenario, f.world, *f.reference, *p);
    CHECK(r.captures_started == 0);
    CHECK(r.summary.faces.requested == 0);
    CHECK(r.summary.faces.granted == 0);
    const auto* baked = static_cast<const BakedPlanner*>(p.get());
    const auto sets =
        static_cast<std::int64_t>(baked->lattice().size() * baked->bake_times().size());
    CHECK(r.summary.bake.captures == sets);
    CHECK(r.summary.bake.faces == 6 * sets);
    CHECK(baked->bake_times().size() == (name == "baked" ? 1u : 8u));
    CHECK(r.summary.probes.max_live == sets);
    CHECK(p->plan(FrameContext{}).empty());
  }
}

TEST_CASE("baked_tod blends the two bake times around the current time linearly", "[baked]") {
  // K = 8 over a 70 s run: bake times 0, 10, ..., 70. Bake k holds the uniform radiance
  // 1 + k^2 (not linear in k, so a wrong pair or weight shows); at time t the lookup is
  // (1 - w) S_k + w S_k+1, k = floor(t / 10), w = t / 10 - k, and S_7 after the end.
  const FlatLevel level(0.0, 40.0);
  auto p = baked_with("baked_tod", {"times=8", "precision=fp32"});
  const auto requests = p->preload(level.context(0.0, 70.0));
  REQUIRE(p->bake_times().size() == 8);
  const std::size_t probes = p->lattice().size();
  REQUIRE(requests.size() == 8 * probes);
  for (std::size_t k = 0; k < 8; ++k) {
    CHECK(p->bake_times()[k] == Approx(10.0 * static_cast<double>(k)));
  }
  for (const auto& r : requests) {
    const std::size_t k = (r.tag - 1) % 8;
    CHECK(r.time == p->bake_times()[k]);
    p->deliver({r.tag, r.position, uniform_sh(static_cast<float>(1 + k * k))});
  }
  const auto expected_at = [](double t) {
    const double u = std::clamp(t / 10.0, 0.0, 7.0);
    const double k = std::min(std::floor(u), 6.0), w = u - k;
    return (1.0 - w) * (1.0 + k * k) + w * (1.0 + (k + 1.0) * (k + 1.0));
  };
  for (double t : {0.0, 4.0, 25.0, 33.0, 59.99, 70.0, 85.0}) {
    INFO("t = " << t);
    p->update(level.context(t, 70.0));
    const LookupResult r = p->lookup({20.2, 0.4, 1.3});
    REQUIRE_FALSE(r.fell_back);
    const double l00 = r.sh.c[0].x / (4.0 * std::numbers::pi * kShY00);
    CHECK(l00 == Approx(expected_at(t)).epsilon(1e-6));
    CHECK(r.data_time == Approx(std::min(t, 70.0)));
  }
  // baked (K = 1) bakes frame 0's light only, and a run of unknown length bakes K = 1 too.
  auto b = baked_with("baked", {});
  const auto frame0 = b->preload(level.context(0.0, 70.0));
  CHECK(std::all_of(frame0.begin(), frame0.end(), [](const auto& r) { return r.time < 0.0; }));
  auto unknown = baked_with("baked_tod", {});
  unknown->preload(level.context(0.0, 0.0));
  CHECK(unknown->bake_times().size() == 1);
}
