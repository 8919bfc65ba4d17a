// The thesis' refresh rule as a clock (policies/core/light_clock.h): ages in closed form.
#include <catch2/catch.hpp>

#include "policies/core/light_clock.h"
#include "tests/support/planner_harness.h"

using namespace ambisim;

namespace {

// Advances `clock` through the frames of [t0, t1) (60 fps) with the world reporting `rate`
// (over each step: the rate at its end). Returns the last frame's time.
double run(LightClock& clock, test::TestWorld& w, double t0, double t1, double rate) {
  w.info.sun_sky_change_rate = rate;
  double last = t0;
  for (int k = 0; t0 + k * test::kFrame < t1 - 1e-9; ++k) {
    FrameContext ctx;
    ctx.time = last = t0 + k * test::kFrame;
    ctx.dt = test::kFrame;
    ctx.world = &w.queries;
    clock.advance(ctx);
  }
  return last;
}

}  // namespace

TEST_CASE("the light clock is real time when off or when the light is still", "[light_clock]") {
  test::TestWorld changing;
  LightClock off(false, 60.0, 0.04);
  const double t_off = run(off, changing, 0.0, 10.0, 0.5);
  CHECK_FALSE(off.running());
  CHECK(off.age(2.0) == t_off - 2.0);  // now - t, bit for bit
  test::TestWorld still;
  still.queries.lighting_static = true;
  LightClock on(true, 60.0, 0.04);
  const double t_on = run(on, still, 0.0, 10.0, 0.5);
  CHECK_FALSE(on.running());
  CHECK(on.age(3.5) == t_on - 3.5);
  CHECK(on.speed() == 1.0);
}

TEST_CASE("the light clock runs at max(1, rate x lifetime / tolerance)", "[light_clock]") {
  test::TestWorld w;
  // 0.01/s with lifetime 60 s and tolerance 0.04: 15x real time; a set lasts 4 s.
  LightClock clock(true, 60.0, 0.04);
  const double now = run(clock, w, 0.0, 20.0, 0.01);
  REQUIRE(clock.running());
  CHECK(clock.speed() == Approx(15.0));
  CHECK(clock.age(now - 4.0) == Approx(60.0).epsilon(1e-9));
  CHECK(clock.age(now - 1.0) == Approx(15.0).epsilon(1e-9));
  // Between frames: linear.
  CHECK(clock.age(now - 1.0 - 0.5 * test::kFrame) == Approx(15.0 * (1.0 + 0.5 * test::kFrame)));
  // A slow rate never slows the clock below real time.
  const double later = run(clock, w, 20.0, 30.0, 0.0001);
  CHECK(clock.speed() == 1.0);
  // Data from 18 s: at 15x up to the last fast frame, then at 1x.
  CHECK(clock.age(18.0) == Approx(15.0 * (now - 18.0) + (later - now)).epsilon(1e-9));
}

TEST_CASE("the light clock dates data from before it started at real speed", "[light_clock]") {
  // The world is still until 10 s (lighting_static), then changes: nothing is older than
  // real time at the start.
  test::TestWorld w;
  w.queries.lighting_static = true;
  LightClock clock(true, 60.0, 0.04);
  run(clock, w, 0.0, 10.0, 0.01);
  CHECK_FALSE(clock.running());
  w.queries.lighting_static = false;
  const double now = run(clock, w, 10.0, 12.0, 0.01);
  REQUIRE(clock.running());
  // From 5 s: 5 s at real speed until the clock starts at 10 s, then ~2 s at 15x.
  CHECK(clock.age(5.0) == Approx(5.0 + 15.0 * (now - 10.0)).epsilon(1e-9));
}
