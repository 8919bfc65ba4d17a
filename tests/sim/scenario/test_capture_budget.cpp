// Capture budget: fractional accumulation patterns, the carry-over cap, counters.
#include <algorithm>
#include <catch2/catch.hpp>

#include "sim/scenario/capture_budget.h"

using namespace ambisim;

namespace {

CaptureBudget make(double faces, int max_carry = 0) {
  CaptureBudgetRecord r;
  r.faces_per_frame = faces;
  r.max_carry_faces = max_carry;
  return CaptureBudget(r);
}

// Faces granted over `frames` frames to a planner that always asks for `ask`.
std::vector<int> pattern(CaptureBudget& b, int frames, int ask) {
  std::vector<int> out;
  for (int k = 0; k < frames; ++k) {
    b.begin_frame(k * 0.01);
    out.push_back(b.grant(ask));
  }
  return out;
}

}  // namespace

TEST_CASE("fractional budgets accumulate into whole faces", "[budget]") {
  auto half = make(0.5);
  CHECK(pattern(half, 6, 6) == std::vector<int>{0, 1, 0, 1, 0, 1});
  auto two_half = make(2.5);
  CHECK(pattern(two_half, 6, 6) == std::vector<int>{2, 3, 2, 3, 2, 3});
  auto one = make(1.0);
  CHECK(pattern(one, 3, 6) == std::vector<int>{1, 1, 1});
  // 0.1 is not exact in binary; the snap still yields exactly one face per ten frames.
  auto tenth = make(0.1);
  const auto p = pattern(tenth, 1000, 6);
  int total = 0;
  for (int k = 0; k < 1000; ++k) {
    total += p[k];
    if (p[k] == 1) CHECK(k % 10 == 9);
  }
  CHECK(total == 100);
}

TEST_CASE("an idle planner cannot bank a burst", "[budget]") {
  SECTION("default: only the fractional part carries") {
    auto b = make(2.5);
    for (int k = 0; k < 20; ++k) b.begin_frame(0.0);  // never asks
    // Credit alternates 2.5 / 3.0: the unused whole faces are dropped each frame.
    CHECK(b.available() == 3);
    CHECK(b.grant(100) == 3);
    b.begin_frame(0.0);
    CHECK(b.available() == 2);
  }
  SECTION("max_carry_faces bounds the burst to carry + ceil(rate)") {
    auto b = make(2.5, 4);
    int max_available = 0;
    for (int k = 0; k < 20; ++k) {
      b.begin_frame(0.0);
      max_available = std::max(max_available, b.available());
    }
    // Credit alternates 6.5 / 7.0 once saturated: 4 carried + 0.5 fraction + 2.5 new.
    CHECK(max_available == 7);
    CHECK(b.available() == 7);  // 20 frames end on the 7.0 phase
    CHECK(b.grant(100) == 7);
  }
}

TEST_CASE("counters split requests into granted and refused", "[budget]") {
  auto b = make(1.0);
  b.begin_frame(0.0);
  CHECK(b.grant(4) == 1);
  CHECK(b.grant(2) == 0);  // the frame's budget is spent
  b.begin_frame(0.01);
  CHECK(b.grant(0) == 0);
  const auto& c = b.counters();
  CHECK(c.frames == 2);
  CHECK(c.requested == 6);
  CHECK(c.granted == 1);
  CHECK(c.refused == 5);
}

TEST_CASE("a budget schedule changes the rate over time", "[budget]") {
  const auto j = nlohmann::json::parse(R"({"schedule": [{"from_s": 0, "faces_per_frame": 1},
      {"from_s": 1, "faces_per_frame": 0.5}], "face_size": 32})");
  ObjectReader r(j, "t.json", "/budget");
  CaptureBudget b(parse_capture_budget(r));
  CHECK(b.face_size() == 32);
  int total = 0;
  for (int k = 0; k < 200; ++k) {  // 100 fps for 2 s: 100 x 1 + 100 x 0.5
    b.begin_frame(k / 100.0);
    total += b.grant(6);
  }
  CHECK(total == 150);
}

TEST_CASE("capture budget JSON errors name the path", "[budget]") {
  auto parse = [](const char* text) {
    const auto j = nlohmann::json::parse(text);
    ObjectReader r(j, "t.json", "/budget");
    return parse_capture_budget(r);
  };
  CHECK(parse("{}").faces_per_frame == 1.0);
  CHECK(parse("{}").face_size == 16);
  CHECK_THROWS_WITH(parse(R"({"faces_per_frame": -1})"),
                    Catch::Contains("/budget/faces_per_frame"));
  CHECK_THROWS_WITH(parse(R"({"face_size": 8.5})"), Catch::Contains("/budget/face_size"));
  CHECK_THROWS_WITH(parse(R"({"faces": 1})"), Catch::Contains("/budget/faces"));
}
