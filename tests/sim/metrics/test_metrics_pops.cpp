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
using ambisim::test::kFps;
using ambisim::test::unit_settings;

namespace {

constexpr double kDeTol = 1e-9;       // dE00 of greys round-tripped through Lab
constexpr double kMinuteTol = 1e-12;  // receiver-minutes summed from 1/60 s steps

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
}

TEST_CASE("the explained move is the projection on the truth's move, clamped to [0, 1] of it",
          "[metrics]") {
  const Lab dr{10, 0, 0};
  const auto same = [](const Lab& a, const Lab& b) {
    return a.L == Approx(b.L).margin(kDeTol) && a.a == Approx(b.a).margin(kDeTol) &&
           a.b == Approx(b.b).margin(kDeTol);
  };
  CHECK(same(explained_move({4, 0, 0}, dr), {4, 0, 0}));         // part of the way
  CHECK(same(explained_move({10, 0, 0}, dr), {10, 0, 0}));       // all of it
  CHECK(same(explained_move({20, 0, 0}, dr), {10, 0, 0}));       // beyond: clamped to 1
  CHECK(same(explained_move({-6, 0, 0}, dr), {0, 0, 0}));        // against: clamped to 0
  CHECK(same(explained_move({5, 7, -3}, dr), {5, 0, 0}));        // across: only the projection
  CHECK(same(explained_move({3, 4, 5}, {0, 0, 0}), {0, 0, 0}));  // the truth is still
}

TEST_CASE("a display that never changes has no pops under any truth", "[metrics]") {
  const Rgb still = grey_of_lightness(50.0, 1.0);
  // The truth steps, ramps, oscillates and jumps back and forth.
  const auto truth = [](int f) {
    const double l = f < 20 ? 30.0 : (f < 40 ? 30.0 + 2.0 * (f - 20) : 70.0 - 30.0 * (f % 2));
    return grey_of_lightness(l, 1.0);
  };
  const Summary s = run_one(
      80, [&](int) { return still; }, truth);
  CHECK(s.pops.count == 0);
  CHECK(s.pops.max == Approx(0.0).margin(kDeTol));
  // Lab moves: a colour step of the truth in a*, b* as well (from grey to a strong green).
  RunMetrics m(unit_settings());
  for (int f = 0; f < 20; ++f) {
    m.begin_frame(f, f / kFps, 1.0 / kFps);
    feed(m, 1, still, f < 10 ? Rgb(0.2f, 0.2f, 0.2f) : Rgb(0.05f, 0.6f, 0.05f));
    m.end_frame();
  }
  CHECK(m.summary().pops.count == 0);
}

TEST_CASE("following the truth exactly, or any fraction of its move, never pops", "[metrics]") {
  // The truth steps 40 -> 70 at frame 10; the planner moves a fraction q of the way at once.
  for (double q : {1.0, 0.75, 0.5, 0.1}) {
    const auto planner = [q](int f) {
      return grey_of_lightness(f < 10 ? 40.0 : 40.0 + 30.0 * q, 1.0);
    };
    const auto truth = [](int f) { return grey_of_lightness(f < 10 ? 40.0 : 70.0, 1.0); };
    const Summary s = run_one(20, planner, truth);
    CAPTURE(q);
    CHECK(s.pops.count == 0);
    CHECK(s.pops.max < 1e-3);  // float greys round-trip to ~1e-4 in L
  }
}

TEST_CASE("a step against the truth's direction is one pop", "[metrics]") {
  const auto planner = [](int f) { return grey_of_lightness(f < 10 ? 50.0 : 45.0, 1.0); };
  const auto truth = [](int f) { return grey_of_lightness(f < 10 ? 50.0 : 60.0, 1.0); };
  const Summary s = run_one(20, planner, truth);
  CHECK(s.pops.count == 1);
  // Nothing of a move against the truth is explained: the whole 5-unit step.
  CHECK(s.pops.max == Approx(grey_de(50, 45)).margin(1e-3));
}

TEST_CASE("twice a 5-unit true step is one pop: the overshoot is unexplained", "[metrics]") {
  const auto planner = [](int f) { return grey_of_lightness(f < 10 ? 50.0 : 60.0, 1.0); };
  const auto truth = [](int f) { return grey_of_lightness(f < 10 ? 50.0 : 55.0, 1.0); };
  const Summary s = run_one(20, planner, truth);
  CHECK(s.pops.count == 1);
  // The explained part is the truth's 5 units; the planner stands 5 units beyond.
  CHECK(s.pops.max == Approx(grey_de(60, 55)).margin(1e-3));
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
  // The reference steps and the planner does not: a lag (accuracy, response time), not a pop.
  CHECK(run_one(20, step(50, 50), step(50, 60)).pops.count == 0);
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

TEST_CASE("masking: a jump that follows a large true jump closely is one jump, not a pop",
          "[metrics]") {
  // The truth jumps from L 40 to 70 (a grey); the planner jumps with it but lands off the line,
  // a* 1.5 units beside it: more than one JND of unexplained change, less than a tenth of the
  // true jump.
  const std::vector<Lab> r0{{40, 0, 0}}, r1{{70, 0, 0}};
  const std::vector<Lab> p0{{40, 0, 0}}, near{{70, 1.5, 0}}, far{{70, 8, 0}};
  const double off = ciede2000(near[0], r1[0]);
  const double jump = ciede2000(r0[0], r1[0]);
  REQUIRE(off > 1.0);
  REQUIRE(off < 0.1 * jump);
  REQUIRE(ciede2000(far[0], r1[0]) > 0.1 * jump);
  const auto pops = [&](double masking, const std::vector<Lab>& landed) {
    PopTracker t(1.0, masking);
    t.update(1, 0, p0, r0);
    return t.update(1, 1, landed, r1);
  };
  CHECK_FALSE(pops(0.1, near).pop);
  CHECK(pops(0.0, near).pop);                                   // the plain definition counts it
  CHECK(pops(0.1, near).change == Approx(off).margin(kDeTol));  // the change is still reported
  CHECK(pops(0.1, far).pop);  // landing far off the true jump stays a pop
  // Masking is by the true jump: the planner's own jump under a still truth is never masked.
  PopTracker t(1.0, 0.1);
  t.update(1, 0, p0, r0);
  CHECK(t.update(1, 1, far, r0).pop);
  // The default settings mask at a tenth.
  CHECK(MetricSettings::defaults().pop_masking == 0.1);
}

TEST_CASE("a camera cut starts every receiver afresh: nothing pops across it", "[metrics]") {
  const Rgb a = grey_of_lightness(40.0, 1.0);
  const Rgb b = grey_of_lightness(70.0, 1.0);
  for (bool cut : {false, true}) {
    RunMetrics m(unit_settings());
    for (int f = 0; f < 20; ++f) {
      m.begin_frame(f, f / kFps, 1.0 / kFps, cut && f == 10);
      feed(m, 7, f < 10 ? a : b, a);  // the display jumps at frame 10; the truth is still
      m.end_frame();
    }
    CAPTURE(cut);
    CHECK(m.summary().pops.count == (cut ? 0 : 1));
  }
}
