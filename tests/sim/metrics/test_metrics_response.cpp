// Response time on synthetic steps of the truth (SPEC section 5).
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "sim/metrics/metrics.h"
#include "sim/metrics/response_time.h"
#include "test_metrics_support.h"

using namespace ambisim;
using ambisim::test::feed;
using ambisim::test::grey_of_lightness;
using ambisim::test::kFps;
using ambisim::test::unit_settings;

namespace {

constexpr double kTimeTol = 1e-9;  // s, sums of 1/60 s steps

// One receiver over `frames` frames; the truth steps from L 40 to 70 at frame 60, the planner
// follows `lag` frames later (a jump), or never (lag < 0).
Summary step_run(int frames, int lag) {
  RunMetrics m(unit_settings());
  for (int f = 0; f < frames; ++f) {
    m.begin_frame(f, f / kFps, 1.0 / kFps);
    const Rgb truth = grey_of_lightness(f < 60 ? 40.0 : 70.0, 1.0);
    const bool followed = lag >= 0 && f >= 60 + lag;
    const Rgb shown = grey_of_lightness(followed ? 70.0 : 40.0, 1.0);
    feed(m, 1, shown, truth);
    m.end_frame();
  }
  return m.summary();
}

}  // namespace

TEST_CASE("response time of a step: the lag until the planner is within 2 dE00", "[metrics]") {
  const Summary instant = step_run(240, 0);
  CHECK(instant.response.events == 1);
  CHECK(instant.response.censored == 0);
  CHECK(instant.response.median_s == Approx(0.0).margin(kTimeTol));

  const Summary lag30 = step_run(240, 30);
  CHECK(lag30.response.events == 1);
  CHECK(lag30.response.median_s == Approx(0.5).margin(kTimeTol));
  CHECK(lag30.response.p95_s == Approx(0.5).margin(kTimeTol));
}

TEST_CASE("a planner that never follows is censored at the receiver's end", "[metrics]") {
  const Summary s = step_run(240, -1);
  CHECK(s.response.events == 1);
  CHECK(s.response.censored == 1);
  // Opened at frame 60 (1 s), the receiver's last frame is 239.
  CHECK(s.response.median_s == Approx(239.0 / kFps - 1.0).margin(kTimeTol));
}

TEST_CASE("no true change, no event, a slow change is no event", "[metrics]") {
  CHECK(step_run(50, -1).response.events == 0);  // ends before the step
  CHECK(std::isnan(step_run(50, -1).response.median_s));
  // The truth drifts 40 -> 70 over 10 s: 1.5 L per 0.5 s, well below 5 dE00.
  RunMetrics m(unit_settings());
  for (int f = 0; f < 600; ++f) {
    m.begin_frame(f, f / kFps, 1.0 / kFps);
    feed(m, 1, grey_of_lightness(40.0, 1.0), grey_of_lightness(40.0 + 30.0 * f / 600.0, 1.0));
    m.end_frame();
  }
  CHECK(m.summary().response.events == 0);
}

TEST_CASE("events at one receiver open at least half a second apart", "[metrics]") {
  // The truth jumps between L 40 and 70 every 6 frames (0.1 s) for 2 s; the planner follows at
  // once. Every jump moves the truth by > 5 dE00, but events are 0.5 s apart: 4 in 2 s.
  ResponseTracker t;
  for (int f = 0; f < 120; ++f) {
    const double l = (f / 6) % 2 == 0 ? 40.0 : 70.0;
    const std::vector<Lab> truth(6, Lab{l, 0, 0});
    t.update(1, f, f / kFps, truth, 0.0);
    t.end_frame(f);
  }
  const ResponseSummary r = t.summary();
  CHECK(r.events == 4);
  CHECK(r.median_s == 0.0);
}
