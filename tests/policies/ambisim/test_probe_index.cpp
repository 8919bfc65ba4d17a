// The ambisim planner's spatial index against brute force, and the planner's indexed lookups
// against its own linear scan (lookup_reference), on random points in and far beyond the world.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <set>

#include "policies/ambisim/demand_planner.h"
#include "policies/ambisim/probe_index.h"
#include "policies/registry/registry.h"
#include "tests/support/planner_harness.h"

using namespace ambisim;

namespace {

// One named tolerance per quantity: the index sums the same terms as the scan in another
// order (float accumulation), so coefficients agree to this, absolutely (values are ~1).
constexpr float kCoefficientTolerance = 1e-6f;
// The far field's cells sum up to thousands of presences in float before they are divided by
// their weight: its coefficients agree with the scan's direct sums to this, absolutely.
constexpr float kIndexFarFieldTolerance = 1e-5f;

std::vector<glm::dvec3> random_points(std::mt19937_64& rng, std::size_t n, double half_extent,
                                      double z_lo, double z_hi) {
  std::uniform_real_distribution<double> xy(-half_extent, half_extent), z(z_lo, z_hi);
  std::vector<glm::dvec3> out(n);
  for (auto& p : out) p = {xy(rng), xy(rng), z(rng)};
  return out;
}

}  // namespace

TEST_CASE("the probe index finds every slot whose radius reaches a point, and the nearest",
          "[ambisim][index]") {
  std::mt19937_64 rng(41);
  const auto positions = random_points(rng, 3000, 200.0, 0.0, 30.0);
  std::vector<double> radii(positions.size());
  // Radii over two decades, so that several levels are occupied.
  std::uniform_real_distribution<double> log_r(std::log(0.3), std::log(30.0));
  for (auto& r : radii) r = std::exp(log_r(rng));
  ProbeIndex index;
  index.build(positions, radii);
  REQUIRE(index.size() == positions.size());
  auto position_of = [&](std::uint32_t i) -> const glm::dvec3& { return positions[i]; };
  auto odd = [](std::uint32_t i) { return i % 2 == 1; };

  auto queries = random_points(rng, 400, 260.0, -10.0, 50.0);
  // Far outside the occupied box, and on cell boundaries.
  for (const glm::dvec3& p : {glm::dvec3(1e6, -1e6, 1e4), glm::dvec3(-5e3, 0.0, 0.0),
                              glm::dvec3(0.0), glm::dvec3(16.0, -8.0, 4.0), positions[17]}) {
    queries.push_back(p);
  }
  for (const glm::dvec3& p : queries) {
    std::set<std::uint32_t> seen;
    bool twice = false;
    index.for_each_candidate(p, [&](std::uint32_t s) { twice |= !seen.insert(s).second; });
    CHECK_FALSE(twice);
    double best = std::numeric_limits<double>::infinity();
    std::int64_t best_slot = -1;
    for (std::uint32_t s = 0; s < positions.size(); ++s) {
      const double d = glm::distance(positions[s], p);
      if (d < radii[s]) CHECK(seen.count(s) == 1);
      if (odd(s) && d < best) {
        best = d;
        best_slot = s;
      }
      const bool within = odd(s) && d <= 3.0;
      if (within) CHECK(index.any_within(p, 3.0, position_of, odd));
    }
    double found = 0.0;
    CHECK(index.nearest(p, position_of, odd, &found) == best_slot);
    CHECK(found == Approx(best).epsilon(1e-12));
  }
  // An empty index answers nothing.
  ProbeIndex empty;
  empty.build({}, {});
  double d = 0.0;
  CHECK(empty.nearest(glm::dvec3(0.0), position_of, odd, &d) == -1);
  CHECK(std::isinf(d));
}

TEST_CASE("the probe index's nearest is the brute force's over terrain, many levels and ties",
          "[ambisim][index]") {
  // Brute force: the least squared distance among accepted slots, ties to the lower slot.
  auto brute = [](const std::vector<glm::dvec3>& positions, const glm::dvec3& p, auto accept) {
    double best2 = std::numeric_limits<double>::infinity();
    std::int64_t best = -1;
    for (std::uint32_t s = 0; s < positions.size(); ++s) {
      if (!accept(s)) continue;
      const glm::dvec3 d = positions[s] - p;
      const double d2 = d.x * d.x + d.y * d.y + d.z * d.z;
      if (d2 < best2) {
        best2 = d2;
        best = s;
      }
    }
    return best;
  };
  std::mt19937_64 rng(43);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  // Over terrain: probes a few metres above hilly ground (200 m of relief), dense along a path
  // and sparse elsewhere, in two levels; each tenth probe repeats an earlier one's position
  // (a tie the lower slot wins). Queries in the same band, near and far from the probes.
  auto ground = [](double x, double y) {
    return 100.0 * std::sin(x / 300.0) * std::cos(y / 250.0);
  };
  std::vector<glm::dvec3> positions;
  std::vector<double> radii;
  for (int i = 0; i < 2000; ++i) {
    glm::dvec3 p;
    if (i % 10 == 9) {
      p = positions[static_cast<std::size_t>(rng() % positions.size())];
    } else if (i % 4 == 0) {
      const double s = 2000.0 * u(rng);
      p = {s - 1000.0, 30.0 * std::sin(s / 90.0), 0.0};
    } else {
      p = {2000.0 * u(rng) - 1000.0, 2000.0 * u(rng) - 1000.0, 0.0};
    }
    p.z = ground(p.x, p.y) + 2.0 + 3.0 * u(rng);
    positions.push_back(p);
    radii.push_back(i % 4 == 0 ? 2.25 : 7.2);
  }
  ProbeIndex index;
  index.build(positions, radii);
  auto position_of = [&](std::uint32_t i) -> const glm::dvec3& { return positions[i]; };
  auto all = [](std::uint32_t) { return true; };
  auto most = [](std::uint32_t i) { return i % 3 != 0; };
  for (int k = 0; k < 600; ++k) {
    const double x = 2400.0 * u(rng) - 1200.0,
                 y = k % 2 ? 40.0 * u(rng) - 20.0 : 2400.0 * u(rng) - 1200.0;
    const glm::dvec3 p{x, y, ground(x, y) + 1.0};
    double d = 0.0;
    INFO("query " << p.x << " " << p.y << " " << p.z);
    CHECK(index.nearest(p, position_of, all, &d) == brute(positions, p, all));
    CHECK(index.nearest(p, position_of, most, &d) == brute(positions, p, most));
  }
  // Radii over 30 octaves: more levels than nearest() interleaves (24); the rest are searched
  // one after another.
  std::vector<glm::dvec3> spread;
  std::vector<double> octaves;
  for (int i = 0; i < 300; ++i) {
    spread.push_back({1000.0 * u(rng) - 500.0, 1000.0 * u(rng) - 500.0, 50.0 * u(rng)});
    octaves.push_back(std::ldexp(0.75, i % 30));
  }
  ProbeIndex deep;
  deep.build(spread, octaves);
  auto spread_of = [&](std::uint32_t i) -> const glm::dvec3& { return spread[i]; };
  for (int k = 0; k < 200; ++k) {
    const glm::dvec3 p{1200.0 * u(rng) - 600.0, 1200.0 * u(rng) - 600.0, 60.0 * u(rng) - 5.0};
    double d = 0.0;
    CHECK(deep.nearest(p, spread_of, most, &d) == brute(spread, p, most));
  }
}

TEST_CASE("cell keys unpack to the coordinates packed", "[ambisim][index]") {
  for (const glm::ivec3 c : {glm::ivec3(0), glm::ivec3(-1, 2, -3), glm::ivec3(kCellCoordLimit - 1),
                             glm::ivec3(-kCellCoordLimit), glm::ivec3(123456, -654321, 7)}) {
    int x = 0, y = 0, z = 0;
    unpack_cell(pack_cell(c.x, c.y, c.z), x, y, z);
    CHECK(glm::ivec3(x, y, z) == c);
  }
}

TEST_CASE("ambisim's indexed lookups equal its linear scan, in and beyond the world",
          "[ambisim][index]") {
  test::TestWorld world;
  world.queries.lighting_static = true;
  // Light that varies with position, so interpolation weights matter.
  world.base_light = [](const glm::dvec3& p, double) {
    return Rgb(0.5f + 0.3f * static_cast<float>(std::sin(p.x / 7.0)),
               0.6f + 0.2f * static_cast<float>(std::cos(p.y / 5.0)), 0.4f);
  };
  auto planner = make_planner("ambisim", planner_params_from_cli("ambisim", {"max_probes=4000"}));
  auto* ambisim = dynamic_cast<DemandPlanner*>(planner.get());
  REQUIRE(ambisim != nullptr);
  test::Harness h(*planner, world);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> spread(-40.0, 40.0);
  std::vector<Planner::ReceiverView> receivers;
  for (std::uint64_t i = 0; i < 60; ++i)
    receivers.push_back({i, {spread(rng), spread(rng), 1.0}, {}});
  planner->set_receivers(receivers);
  std::size_t compared = 0, far_only = 0, mixed = 0, blended = 0;
  // A camera circling through the receivers; compare at several moments, probes fading in.
  for (int round = 0; round < 6; ++round) {
    const double until = h.time() + 2.5;
    while (h.time() < until) {
      const double a = 0.2 * h.time();
      h.camera = {30.0 * std::cos(a), 30.0 * std::sin(a), 1.2};
      h.step();
    }
    auto points = random_points(rng, 300, 45.0, 0.0, 3.0);
    points.push_back({1e5, -3e4, 50.0});
    points.push_back({2000.0, 2000.0, -500.0});
    LookupPoints batch;
    for (const auto& p : points) batch.push_back(p);
    std::vector<LookupResult> many;
    planner->lookup_many(batch, many);
    REQUIRE(many.size() == points.size());
    for (std::size_t k = 0; k < points.size(); ++k) {
      const LookupResult fast = planner->lookup(points[k]);
      const LookupResult slow = ambisim->lookup_reference(points[k]);
      INFO("point " << points[k].x << " " << points[k].y << " " << points[k].z);
      CHECK(fast.fell_back == slow.fell_back);
      REQUIRE(fast.contributor_count == slow.contributor_count);
      for (int c = 0; c < fast.contributor_count; ++c) {
        CHECK(fast.contributors[c].tag == slow.contributors[c].tag);
        CHECK(std::abs(fast.contributors[c].weight - slow.contributors[c].weight) <=
              kCoefficientTolerance);
      }
      for (int i = 0; i < kShCount; ++i) {
        for (int ch = 0; ch < 3; ++ch) {
          CHECK(std::abs(fast.sh.c[i][ch] - slow.sh.c[i][ch]) <=
                (ambisim->lookup_uses_far_field(points[k]) ? kIndexFarFieldTolerance
                                                           : kCoefficientTolerance));
        }
      }
      // Data times are summed in float far-field cells: relative.
      CHECK(
          fast.data_time ==
          Approx(slow.data_time).epsilon(ambisim->lookup_uses_far_field(points[k]) ? 1e-6 : 1e-9));
      CHECK(fast.spacing_m == Approx(slow.spacing_m).epsilon(1e-9));
      // The batch is the single lookup, exactly.
      CHECK(many[k].sh == fast.sh);
      CHECK(many[k].contributor_count == fast.contributor_count);
      ++compared;
      const bool far = ambisim->lookup_uses_far_field(points[k]);
      far_only += far && fast.contributor_count == 0 ? 1 : 0;
      mixed += far && fast.contributor_count > 0 ? 1 : 0;
      blended += !far && fast.contributor_count >= 2 ? 1 : 0;
    }
  }
  CHECK(compared == 6 * 302);
  CHECK(planner->stats().live_probes >= 60);
  // Every kind of answer was compared: bumps alone, bumps mixed with the far field at the edge
  // of their reach, and the far field alone (at least the 12 points far outside the world).
  INFO("far field alone " << far_only << ", mixed " << mixed << ", bumps " << blended);
  CHECK(far_only >= 12);
  CHECK(mixed >= 100);
  CHECK(blended >= 50);
}
