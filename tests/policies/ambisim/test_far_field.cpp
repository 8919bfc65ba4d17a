// The ambisim planner's far field (policies/ambisim/far_field.h) against closed forms (a
// constant field is reproduced, one probe answers everywhere, a far point gets the weighted
// mean), against its own reference scan, and for continuity in space and in the probes' weights.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <random>

#include "policies/ambisim/far_field.h"

using namespace ambisim;

namespace {

// The cells sum in float before dividing by their weight (the reference sums directly).
constexpr float kFarFieldTolerance = 1e-5f;
// Data times are summed (weighted) in float cells: relative.
constexpr double kTimeTolerance = 1e-6;

struct Cloud {
  std::vector<glm::dvec3> positions;
  std::vector<double> weights;
  std::vector<Sh9Rgb> values;
  void add_to(std::size_t i, FarField::Sums& s) const {
    s.sh += values[i] * static_cast<float>(weights[i]);
    s.weight += weights[i];
    s.time += weights[i] * static_cast<double>(i);
  }
};

Sh9Rgb value_of(float a, float b, float c) {
  Sh9Rgb v;
  for (int k = 0; k < kShCount; ++k) {
    v.c[static_cast<std::size_t>(k)] = Rgb(a, b, c) * (1.0f / static_cast<float>(k + 1));
  }
  return v;
}

// Probes on a patch of ground, as the planner leaves them: a 3 m lattice, jittered.
Cloud patch(std::mt19937_64& rng, double half_m, double cx, double cy) {
  Cloud c;
  std::uniform_real_distribution<double> jitter(-1.0, 1.0), unit(0.0, 1.0);
  for (double x = -half_m; x <= half_m; x += 3.0) {
    for (double y = -half_m; y <= half_m; y += 3.0) {
      c.positions.push_back({cx + x + jitter(rng), cy + y + jitter(rng), 2.0 + jitter(rng)});
      c.weights.push_back(unit(rng));
      c.values.push_back(value_of(static_cast<float>(unit(rng)), static_cast<float>(unit(rng)),
                                  static_cast<float>(unit(rng))));
    }
  }
  return c;
}

FarField filled(const Cloud& c) {
  FarField f;
  f.build(c.positions);
  f.fill([&](std::size_t i, FarField::Sums& s) { c.add_to(i, s); });
  return f;
}

double max_difference(const Sh9Rgb& a, const Sh9Rgb& b) {
  double d = 0.0;
  for (int k = 0; k < kShCount; ++k) {
    for (int ch = 0; ch < 3; ++ch) {
      const auto i = static_cast<std::size_t>(k);
      d = std::max(d, static_cast<double>(std::abs(a.c[i][ch] - b.c[i][ch])));
    }
  }
  return d;
}

}  // namespace

TEST_CASE("the far field reproduces a constant field and a single probe everywhere",
          "[ambisim][far_field]") {
  std::mt19937_64 rng(3);
  Cloud c = patch(rng, 30.0, 100.0, -50.0);
  const Sh9Rgb v = value_of(0.7f, 0.2f, 0.4f);
  for (auto& x : c.values) x = v;
  const FarField f = filled(c);
  std::uniform_real_distribution<double> where(-2000.0, 2000.0);
  for (int k = 0; k < 500; ++k) {
    const glm::dvec3 p{where(rng), where(rng), 0.01 * where(rng)};
    FarField::Answer a;
    REQUIRE(f.evaluate(p, a));
    CHECK(max_difference(a.sh, v) <= kFarFieldTolerance);
  }
  // One probe: its value, wherever the point, however faint its presence.
  Cloud one;
  one.positions = {{-3.0, 7.0, 1.0}};
  one.weights = {0.01};
  one.values = {value_of(0.3f, 0.9f, 0.1f)};
  const FarField g = filled(one);
  for (const glm::dvec3 p : {glm::dvec3{-3, 7, 1}, glm::dvec3{40, -90, 3}, glm::dvec3{1e6, 0, 0}}) {
    FarField::Answer a;
    REQUIRE(g.evaluate(p, a));
    CHECK(max_difference(a.sh, one.values[0]) <= kFarFieldTolerance);
    CHECK(a.data_time == Approx(0.0).margin(1e-12));
  }
  // Nothing present: no answer.
  one.weights = {0.0};
  FarField::Answer a;
  CHECK_FALSE(filled(one).evaluate({0, 0, 0}, a));
}

TEST_CASE("the far field far beyond every probe is their mean weighted by presence",
          "[ambisim][far_field]") {
  std::mt19937_64 rng(4);
  const Cloud c = patch(rng, 20.0, 0.0, 0.0);
  Sh9Rgb mean;
  double w = 0.0, t = 0.0;
  for (std::size_t i = 0; i < c.positions.size(); ++i) {
    mean += c.values[i] * static_cast<float>(c.weights[i]);
    w += c.weights[i];
    t += c.weights[i] * static_cast<double>(i);
  }
  mean *= static_cast<float>(1.0 / w);
  FarField::Answer a;
  // 50 km away: no level's cells reach the point (the coarsest are 4 km).
  REQUIRE(filled(c).evaluate({5e4, -3e4, 10.0}, a));
  CHECK(max_difference(a.sh, mean) <= kFarFieldTolerance);
  CHECK(a.data_time == Approx(t / w).epsilon(kTimeTolerance));
  CHECK(a.cell_m > FarField::kBaseCellM * (1 << (FarField::kLevels - 1)));
}

TEST_CASE("the far field equals its reference scan, in and far beyond the probes",
          "[ambisim][far_field]") {
  std::mt19937_64 rng(5);
  // Two patches of different sizes and densities, and a few strays.
  Cloud c = patch(rng, 40.0, 0.0, 0.0);
  const Cloud d = patch(rng, 10.0, 300.0, 120.0);
  for (std::size_t i = 0; i < d.positions.size(); ++i) {
    c.positions.push_back(d.positions[i]);
    c.weights.push_back(d.weights[i]);
    c.values.push_back(d.values[i]);
  }
  c.positions.push_back({-900.0, 400.0, 30.0});
  c.weights.push_back(1.0);
  c.values.push_back(value_of(1.0f, 0.0f, 0.0f));
  // Probes appended after the build, as the planner delivers them, fill as the built ones.
  FarField f;
  f.build(std::span(c.positions).first(c.positions.size() - 5));
  for (std::size_t i = c.positions.size() - 5; i < c.positions.size(); ++i)
    f.append(c.positions[i]);
  REQUIRE(f.size() == c.positions.size());
  f.fill([&](std::size_t i, FarField::Sums& s) { c.add_to(i, s); });
  std::uniform_real_distribution<double> near(-80.0, 380.0), far(-3e3, 3e3), z(-5.0, 40.0);
  int compared = 0;
  for (int k = 0; k < 400; ++k) {
    const glm::dvec3 p = k % 4 == 0 ? glm::dvec3{far(rng), far(rng), z(rng)}
                                    : glm::dvec3{near(rng), near(rng), z(rng)};
    FarField::Answer fast, slow;
    REQUIRE(f.evaluate(p, fast));
    REQUIRE(FarField::evaluate_reference(
        p, c.positions, [&](std::size_t i, FarField::Sums& s) { c.add_to(i, s); }, slow));
    INFO("point " << p.x << " " << p.y << " " << p.z);
    CHECK(max_difference(fast.sh, slow.sh) <= kFarFieldTolerance);
    CHECK(fast.data_time == Approx(slow.data_time).epsilon(kTimeTolerance));
    CHECK(fast.cell_m == slow.cell_m);
    ++compared;
  }
  CHECK(compared == 400);
}

TEST_CASE("far field: a batch's corner memo gives the same answers, bit for bit",
          "[ambisim][far_field]") {
  std::mt19937_64 rng(8);
  Cloud c = patch(rng, 40.0, 0.0, 0.0);
  const Cloud d = patch(rng, 6.0, 200.0, -60.0);
  for (std::size_t i = 0; i < d.positions.size(); ++i) {
    c.positions.push_back(d.positions[i]);
    c.weights.push_back(d.weights[i]);
    c.values.push_back(d.values[i]);
  }
  const FarField f = filled(c);
  // Points that repeat blocks (a dense cloud), that do not (spread over 6 km), and far beyond
  // the clamped cells (where no block is memoised), in one batch.
  std::vector<glm::dvec3> points;
  std::uniform_real_distribution<double> dense(-50.0, 50.0), spread(-3e3, 3e3), z(-5.0, 30.0);
  for (int k = 0; k < 3000; ++k) {
    const int kind = k % 10;
    points.push_back(kind < 7   ? glm::dvec3{dense(rng), dense(rng), z(rng)}
                     : kind < 9 ? glm::dvec3{spread(rng), spread(rng), z(rng)}
                                : glm::dvec3{spread(rng) * 1e4, 2e7, z(rng)});
  }
  // A memo of 16 blocks per level (a batch of one) evicts all the time; one for the whole batch
  // mostly hits. Both must leave every answer as it is without a memo.
  for (std::size_t batch : {std::size_t{1}, points.size()}) {
    FarField::CornerMemo memo(batch);
    int same = 0;
    for (const glm::dvec3& p : points) {
      FarField::Answer plain, memoised;
      REQUIRE(f.evaluate(p, plain));
      REQUIRE(f.evaluate(p, memoised, &memo));
      INFO("batch " << batch << ", point " << p.x << " " << p.y << " " << p.z);
      REQUIRE(std::memcmp(&plain.sh, &memoised.sh, sizeof(Sh9Rgb)) == 0);
      REQUIRE(plain.data_time == memoised.data_time);
      REQUIRE(plain.cell_m == memoised.cell_m);
      ++same;
    }
    CHECK(same == static_cast<int>(points.size()));
  }
}

TEST_CASE("the far field is continuous along a path and in a probe's presence",
          "[ambisim][far_field]") {
  std::mt19937_64 rng(6);
  Cloud c = patch(rng, 30.0, 0.0, 0.0);
  const FarField f = filled(c);
  // A 400 m line from inside the patch out past it, in 1 mm steps: no step changes the answer
  // by more than a smooth field would (a slope of 1 per metre; a jump between cells or levels
  // would be of the order of the differences between cells' means, 0.01 to 0.5).
  const glm::dvec3 a{-10.0, -7.0, 1.5}, b{390.0, 60.0, 12.0};
  const int steps = 400000;
  FarField::Answer prev;
  REQUIRE(f.evaluate(a, prev));
  double worst = 0.0, travelled = 0.0;
  for (int k = 1; k <= steps; ++k) {
    FarField::Answer now;
    REQUIRE(f.evaluate(a + (b - a) * (static_cast<double>(k) / steps), now));
    const double d = max_difference(now.sh, prev.sh);
    worst = std::max(worst, d);
    travelled += d;
    prev = now;
  }
  INFO("largest step " << worst << ", total variation " << travelled);
  CHECK(worst < 1e-3);
  CHECK(travelled > 0.05);  // the answer did change along the way
  // A probe arriving far from the others, at a level-0 cell centre: at presence 1e-6 it moves
  // the answer there by about 1e-6 (not to its own value); at presence 1 its cell alone reaches
  // kConfidence, so the answer there is its value.
  const glm::dvec3 spot{18.5 * FarField::kBaseCellM, 18.5 * FarField::kBaseCellM,
                        0.5 * FarField::kBaseCellM};
  FarField::Answer without, faint, full;
  REQUIRE(f.evaluate(spot, without));
  c.positions.push_back(spot);
  c.values.push_back(value_of(5.0f, 5.0f, 5.0f));
  c.weights.push_back(1e-6);
  REQUIRE(filled(c).evaluate(spot, faint));
  c.weights.back() = 1.0;
  REQUIRE(filled(c).evaluate(spot, full));
  CHECK(max_difference(faint.sh, without.sh) < 1e-4);
  CHECK(max_difference(full.sh, c.values.back()) <= kFarFieldTolerance);
}

TEST_CASE("far field: refilling the marked slots' cells equals a full fill, bit for bit",
          "[ambisim][far_field]") {
  // Two patches far apart, so some coarse cells hold no marked slot. Probes are appended
  // between refills, which keep the member lists (not a full refill): into a cell that holds
  // slots, into a new cell beside the patch and into new cells of every level far away (two in
  // one round: a new cell's second member). The oracle is fill() over the same slots and
  // values.
  std::mt19937_64 rng(41);
  Cloud c = patch(rng, 60.0, 0.0, 0.0);
  const Cloud far = patch(rng, 30.0, 900.0, -400.0);
  c.positions.insert(c.positions.end(), far.positions.begin(), far.positions.end());
  c.weights.insert(c.weights.end(), far.weights.begin(), far.weights.end());
  c.values.insert(c.values.end(), far.values.begin(), far.values.end());
  FarField incremental;
  incremental.build(c.positions);
  auto add = [&](std::size_t i, FarField::Sums& s) { c.add_to(i, s); };
  incremental.refill_marked(add);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::uniform_int_distribution<std::size_t> pick(0, c.positions.size() - 1);
  const std::vector<glm::dvec3> points = {
      {1.0, 2.0, 3.0},   {25.0, -40.0, 1.0},        {905.0, -390.0, 2.0}, {450.0, -200.0, 50.0},
      {70.0, 12.0, 3.0}, {20e3 - 10.0, -35e3, 8.0}, {15e3, -30e3, 100.0}};
  for (int round = 0; round < 20; ++round) {
    auto append = [&](const glm::dvec3& at) {
      c.positions.push_back(at);
      c.weights.push_back(unit(rng));
      c.values.push_back(value_of(0.2f, 0.3f, static_cast<float>(unit(rng))));
      incremental.append(at);
    };
    if (round == 3) append({1.5, 2.5, 2.0});      // a cell of the first patch
    if (round == 7) append({70.0, 10.0, 2.0});    // a new level-0 cell beside it
    if (round == 11) append({20e3, -35e3, 9.0});  // new cells up to the coarsest level
    if (round == 13) {
      append({20e3 + 3.0, -35e3 + 1.0, 9.0});  // the same cell again, and one beside it
      append({20e3 - 40.0, -35e3 + 20.0, 9.0});
    }
    if (round == 17) append({905.0, -395.0, 2.0});  // a cell of the far patch
    for (int k = 0; k < 5; ++k) {
      const std::size_t i = pick(rng);
      c.weights[i] = unit(rng);
      incremental.mark(i);
    }
    incremental.refill_marked(add);
    const FarField full = filled(c);
    for (const auto& p : points) {
      FarField::Answer a, b;
      REQUIRE(incremental.evaluate(p, a) == full.evaluate(p, b));
      for (std::size_t k = 0; k < a.sh.c.size(); ++k) {
        for (int ch = 0; ch < 3; ++ch) REQUIRE(a.sh.c[k][ch] == b.sh.c[k][ch]);
      }
      REQUIRE(a.data_time == b.data_time);
      REQUIRE(a.cell_m == b.cell_m);
    }
  }
}
