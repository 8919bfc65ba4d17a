// Frame schedules: exact frame counts and drift-free frame times.
#include <catch2/catch.hpp>
#include <cmath>

#include "sim/scenario/frame_schedule.h"

using namespace ambisim;

namespace {

// Frame times are k / fps (+ a segment start): one rounding. Measured error against the
// hand-written times of the 100/10/100 schedule: 0 s; on the ramp, N(time_of(k)) - k: 6e-14.
constexpr double kTimeTol = 1e-12;  // s

FrameSchedule make(std::vector<FpsSegment> segments, double duration) {
  FrameScheduleRecord r;
  r.segments = std::move(segments);
  r.duration_s = duration;
  return FrameSchedule(r);
}

FrameScheduleRecord parse_schedule(const char* text) {
  const auto j = nlohmann::json::parse(text);
  ObjectReader r(j, "test.json", "/frames");
  return parse_frame_schedule(r);
}

}  // namespace

TEST_CASE("constant frame rate gives duration x fps frames with equal steps", "[frames]") {
  const FrameSchedule s = make({{0.0, 60.0, false}}, 10.0);
  CHECK(s.frame_count() == 600);
  FrameClock clock(s);
  Frame f;
  std::int64_t n = 0;
  while (clock.next(f)) {
    CHECK(f.index == n);
    CHECK(f.time == Approx(n / 60.0).margin(kTimeTol));
    CHECK(f.dt == Approx(1.0 / 60.0).margin(kTimeTol));
    ++n;
  }
  CHECK(n == 600);
}

TEST_CASE("100 -> 10 -> 100 fps gives the exact number of frames", "[frames]") {
  // 5 s at 100, 5 s at 10, 5 s at 100: 500 + 50 + 500.
  const auto rec = parse_schedule(R"({"duration_s": 15, "segments": [
      {"from_s": 0, "fps": 100}, {"from_s": 5, "fps": 10}, {"from_s": 10, "fps": 100}]})");
  const FrameSchedule s(rec);
  CHECK(s.frame_count() == 1050);
  CHECK(s.frame(500).time == Approx(5.0).margin(kTimeTol));
  CHECK(s.frame(500).dt == Approx(0.01).margin(kTimeTol));  // last 100 fps step
  CHECK(s.frame(501).dt == Approx(0.1).margin(kTimeTol));
  CHECK(s.frame(550).time == Approx(10.0).margin(kTimeTol));
  CHECK(s.frame(551).dt == Approx(0.01).margin(kTimeTol));
  CHECK(s.frame(1049).time == Approx(14.99).margin(kTimeTol));
}

TEST_CASE("a rate change off the frame grid keeps the frame phase continuous", "[frames]") {
  // N(t) = 30 * 1.01 + 60 (t - 1.01): N(2) = 89.7, so frames 0..89 lie before 2 s.
  const FrameSchedule s = make({{0.0, 30.0, false}, {1.01, 60.0, false}}, 2.0);
  CHECK(s.frame_count() == 90);
  // Frame 31 is 0.7 frame-steps of 60 fps after 1.01 s.
  CHECK(s.frame(31).time == Approx(1.01 + 0.7 / 60.0).margin(kTimeTol));
}

TEST_CASE("a linear fps ramp places frames where the frame integral is whole", "[frames]") {
  // 100 fps falling linearly to 10 fps over 10 s: N(10) = 55 * 10 = 550 frames.
  const FrameSchedule s = make({{0.0, 100.0, true}, {10.0, 10.0, false}}, 10.0);
  CHECK(s.frame_count() == 550);
  CHECK(s.fps_at(5.0) == Approx(55.0));
  // N(t) = 100 t - 4.5 t^2: frame 319 is at the smaller root of N(t) = 319.
  const double t319 = (100.0 - std::sqrt(100.0 * 100.0 - 4.0 * 4.5 * 319.0)) / (2.0 * 4.5);
  CHECK(s.frame(319).time == Approx(t319).margin(kTimeTol));
  double prev_dt = 0.0;
  for (std::int64_t k = 1; k < 550; ++k) {
    const double dt = s.frame(k).dt;
    CHECK(dt >= prev_dt);  // frames spread out as the rate falls
    prev_dt = dt;
  }
  CHECK(s.frame(550).time == Approx(10.0).margin(kTimeTol));
}

TEST_CASE("frame times do not drift over a million frames", "[frames]") {
  const FrameSchedule s = make({{0.0, 60.0, false}}, 1e6);
  // Summing 1/60 a million times drifts by ~1e-9 s; k / fps is one rounding.
  CHECK(s.time_of(1000000) == 1000000.0 / 60.0);
  CHECK(s.frame_count() == 60000000);
}

TEST_CASE("frame schedule JSON errors name the path", "[frames]") {
  CHECK(FrameSchedule(parse_schedule(R"({"fps": 25, "duration_s": 2})")).frame_count() == 50);
  CHECK_THROWS_WITH(parse_schedule(R"({"fps": 0})"), Catch::Contains("/frames/fps"));
  CHECK_THROWS_WITH(parse_schedule(R"({"segments": [{"from_s": 1, "fps": 10}]})"),
                    Catch::Contains("/frames/segments/0/from_s"));
  CHECK_THROWS_WITH(
      parse_schedule(R"({"segments": [{"from_s": 0, "fps": 10, "ramp_to_next": true}]})"),
      Catch::Contains("ramp_to_next"));
  CHECK_THROWS_WITH(parse_schedule(R"({"fps": 10, "fsp": 2})"), Catch::Contains("/frames/fsp"));
}
