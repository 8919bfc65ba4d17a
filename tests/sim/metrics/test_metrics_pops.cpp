// Colour pops: steps, fades and explained changes, and the per-receiver-minute arithmetic.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "sim/colour/ciede2000.h"
#include "sim/colour/tone_map.h"
#include "sim/metrics/colour_pops.h"
#include "sim/metrics/metrics.h"
#include "test_metrics_support.h"

using namespace ambisim;
using ambisim::test::feed;
using ambisim::test::grey_of_lightness;
using ambisim::test::grey_value_of_lightness;
using ambisim::test::unit_settings;

namespace {

constexpr double kDeTol = 1e-9;       // dE00 of greys round-tripped through Lab
constexpr double kMinuteTol = 1e-12;  // receiver-minutes summed from 1/60 s steps
constexpr double kFps = 60.0;

// dE00 between two greys of lightness a and b (a* = b* = 0): |a - b| / S_L with
// S_L = 1 + 0.015 (Lm - 50)^2 / sqrt(20 + (Lm - 50)^2), Lm the mean lightness (CIE 142-2001).
double grey_de(double a, double b) {
  const double m = 0.5 * (a + b) - 50.0;
  return std::abs(a - b) / (1.0 + 0.015 * m * m / std::sqrt(20.0 + m * m));
}

// Runs one receiver for `frames` frames at 60 fps with planner(t) and reference(t).
template <typename P, typename R>
Summary run_one(int frames, P planner, R reference) {
  RunMetrics m(unit_settings());
  for (int f = 0; f < frames; ++f) {
    m.begin_frame(f, f / kFps, 1.0 / kFps);
    feed(m, 7, planner(f), reference(f));
    m.end_frame();
  }
  return m.summary();
}

}  // namespace

TEST_CASE("the test greys have the intended displayed lightness", "[metrics]") {
  for (double lightness : {30.0, 50.0, 60.0, 90.0}) {
    const Lab lab = display_lab(grey_of_lightness(lightness, 1.0), 1.0);
    CHECK(lab.L == Approx(lightness).margin(1e-4));  // float irradiance
    CHECK(std::abs(lab.a) < 1e-4);
  }
  CHECK(ciede2000({50, 0, 0}, {60, 0, 0}) == Approx(grey_de(50, 60)).margin(kDeTol));
}

TEST_CASE("unexplained change is 0 when the planner moves exactly like the reference",
          "[metrics]") {
  const Lab p0{40, 10, -5}, r0{50, 0, 0}, r1{55, 3, 1};
  CHECK(unexplained_change(p0, p0 + (r1 - r0), r0, r1) == Approx(0.0).margin(kDeTol));
  CHECK(unexplained_change(p0, p0, r0, r0) == 0.0);
  // Planner static while the reference moves: the whole reference move is unexplained.
  CHECK(unexplained_change(Lab{50, 0, 0}, Lab{50, 0, 0}, Lab{50, 0, 0}, Lab{60, 0, 0}) ==
        Approx(grey_de(50, 60)).margin(kDeTol));
}

TEST_CASE("a 10-unit lightness step with a constant reference is exactly one pop", "[metrics]") {
  const Rgb before = grey_of_lightness(50.0, 1.0);
  const Rgb after = grey_of_lightness(60.0, 1.0);
  const Rgb reference = grey_of_lightness(55.0, 1.0);
  const Summary s = run_one(
      20, [&](int f) { return f < 10 ? before : after; }, [&](int) { return reference; });
  CHECK(s.pops.count == 1);  // six normals exceed the threshold in the same frame: one pop
  CHECK(s.pops.max == Approx(grey_de(50, 60)).margin(1e-3));  // float greys: L to ~1e-4
  CHECK(s.pops.sum == s.pops.max);
}

TEST_CASE("the same step faded linearly over 0.5 s at 60 fps is no pop", "[metrics]") {
  const double v0 = grey_value_of_lightness(50.0, 1.0);
  const double v1 = grey_value_of_lightness(60.0, 1.0);
  const int fade_frames = static_cast<int>(0.5 * kFps);  // 30
  const auto planner = [&](int f) {
    const double u = std::clamp((f - 10) / double(fade_frames), 0.0, 1.0);
    return Rgb(static_cast<float>(v0 + u * (v1 - v0)));
  };
  const Rgb reference = grey_of_lightness(55.0, 1.0);
  const Summary s = run_one(60, planner, [&](int) { return reference; });
  CHECK(s.pops.count == 0);
  // It did move: about 10 / 30 per frame, and below one JND.
  CHECK(s.pops.max > 0.25);
  CHECK(s.pops.max < 0.5);
  CHECK(s.pops.sum == 0.0);

  // The same fade squeezed into 5 frames moves ~2 units a frame: a pop every frame of it.
  const auto fast = [&](int f) {
    const double u = std::clamp((f - 10) / 5.0, 0.0, 1.0);
    return Rgb(static_cast<float>(v0 + u * (v1 - v0)));
  };
  CHECK(run_one(60, fast, [&](int) { return reference; }).pops.count == 5);
}

TEST_CASE("a step the reference also makes is no pop", "[metrics]") {
  // Identical step in both.
  const auto step = [](double from, double to) {
    return [=](int f) { return grey_of_lightness(f < 10 ? from : to, 1.0); };
  };
  const Summary same = run_one(20, step(50, 60), step(50, 60));
  CHECK(same.pops.count == 0);
  CHECK(same.pops.max == Approx(0.0).margin(kDeTol));
  // The planner 2 units darker than the reference but making the same 10-unit step.
  const Summary offset = run_one(20, step(48, 58), step(50, 60));
  CHECK(offset.pops.count == 0);
  CHECK(offset.pops.max < 1e-3);
  // The reference steps and the planner does not: that is a pop.
  CHECK(run_one(20, step(50, 50), step(50, 60)).pops.count == 1);
}

TEST_CASE("pops per receiver-minute on a hand-built run", "[metrics]") {
  // 3 receivers x 1200 frames at 60 fps = 60 receiver-seconds, minus receiver 3's 20-frame
  // absence. Receiver 1 steps up at frame 100 and back at 200 (2 pops); receiver 2 steps at 500
  // (1 pop); receiver 3 comes back from its absence at 620 with a different colour: a first
  // frame, no pop.
  const Rgb a = grey_of_lightness(50.0, 1.0);
  const Rgb b = grey_of_lightness(60.0, 1.0);
  RunMetrics m(unit_settings());
  std::int64_t pops_at_100 = -1;
  for (int f = 0; f < 1200; ++f) {
    m.begin_frame(f, f / kFps, 1.0 / kFps);
    feed(m, 1, (f >= 100 && f < 200) ? b : a, a);
    feed(m, 2, f >= 500 ? b : a, a);
    if (f < 600 || f >= 620) feed(m, 3, f >= 620 ? b : a, a);
    const FrameRow row = m.end_frame();
    if (f == 100) pops_at_100 = row.pops;
  }
  const Summary s = m.summary();
  const double receiver_minutes = (3.0 * 1200.0 - 20.0) / kFps / 60.0;
  CHECK(pops_at_100 == 1);
  CHECK(s.receiver_frames == 3 * 1200 - 20);
  CHECK(s.receiver_minutes == Approx(receiver_minutes).margin(kMinuteTol));
  CHECK(s.pops.count == 3);
  CHECK(s.pops.per_min == Approx(3.0 / receiver_minutes).epsilon(1e-12));
  CHECK(s.pops.sum == Approx(3.0 * s.pops.max).epsilon(1e-9));  // 50->60 and 60->50 alike
  CHECK(s.pops.max == Approx(grey_de(50, 60)).margin(1e-3));
}

TEST_CASE("pop tracker: gaps break the chain, duplicates are errors", "[metrics]") {
  PopTracker t(1.0);
  const std::vector<Lab> x{{50, 0, 0}}, y{{70, 0, 0}};
  CHECK_FALSE(t.update(1, 0, x, x).has_previous);
  t.end_frame(0);
  CHECK(t.update(1, 1, y, x).pop);
  CHECK_THROWS_AS(t.update(1, 1, y, x), std::logic_error);
  t.end_frame(1);
  t.end_frame(2);  // receiver 1 missing in frame 2: forgotten
  CHECK(t.tracked() == 0);
  const PopEvaluation back = t.update(1, 3, x, x);
  CHECK_FALSE(back.has_previous);
  CHECK_FALSE(back.pop);
}
