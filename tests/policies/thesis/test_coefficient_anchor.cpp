// CoefficientAnchor (thesis Bilaga B, D6-D8): fade-in, re-request before expiry, serving the
// old set while the replacement is in flight.
#include <catch2/catch.hpp>

#include "policies/thesis/coefficient_anchor.h"

using namespace ambisim;

namespace {

Sh9Rgb uniform(float v) {
  Sh9Rgb s;
  for (auto& c : s.c) c = Rgb(v, 2.0f * v, 3.0f * v);
  return s;
}

AnchorTiming timing() {
  AnchorTiming t;
  t.lifetime_s = 60.0;
  t.fade_s = 1.0;
  t.margin_s = 1.2;  // 2 x 0.1 s latency + 1 s (D7)
  return t;
}

}  // namespace

TEST_CASE("a fresh anchor without a previous value snaps in", "[shgraph]") {
  CoefficientAnchor a;
  CHECK_FALSE(a.has_coefficients());
  a.prepare_for_new();
  CHECK(a.in_flight());
  a.set_new(uniform(1.0f), 0.0, 7, nullptr, 0.0);
  CHECK(a.has_coefficients());
  CHECK_FALSE(a.in_flight());
  a.update(0.2, timing());
  CHECK(a.active() == uniform(1.0f));
  CHECK(a.tag() == 7);
}

TEST_CASE("new coefficients fade in linearly over fade_s from the previous value", "[shgraph]") {
  CoefficientAnchor a;
  const Sh9Rgb before = uniform(1.0f);
  a.set_new(uniform(3.0f), 10.0, 1, &before, 4.0);
  // The fade starts at the first update after delivery: that frame still shows `before`.
  a.update(10.5, timing());
  CHECK(a.active() == before);
  CHECK(a.data_time() == Approx(4.0));
  a.update(10.75, timing());
  CHECK(a.active().c[0].x == Approx(1.5f));  // a quarter of the way
  a.update(11.0, timing());
  CHECK(a.active().c[4].y == Approx(4.0f));  // half way: 2 -> 6
  a.update(11.5, timing());
  CHECK(a.active() == uniform(3.0f));
  CHECK_FALSE(a.fading());
  CHECK(a.data_time() == Approx(10.0));
}

TEST_CASE(
    "need_new is raised lifetime - margin after capture, and the old set is served while "
    "the replacement is in flight",
    "[shgraph]") {
  CoefficientAnchor a;
  a.set_new(uniform(1.0f), 0.0, 1, nullptr, 0.0);
  a.update(0.0, timing());
  CHECK_FALSE(a.update(58.7, timing()));
  CHECK_FALSE(a.need_new());
  a.update(58.9, timing());
  CHECK(a.need_new());
  a.prepare_for_new();
  a.update(59.0, timing());
  CHECK_FALSE(a.need_new());  // in flight: not asked again
  // Past the lifetime but within lifetime + fade: still served.
  CHECK_FALSE(a.update(60.5, timing()));
  CHECK(a.has_coefficients());
  // The replacement arrives and fades from the old set.
  a.set_new(uniform(2.0f), 59.0, 2, nullptr, 0.0);
  a.update(60.6, timing());
  CHECK(a.active() == uniform(1.0f));
  a.update(61.6, timing());
  CHECK(a.active() == uniform(2.0f));
  CHECK(a.creation_time() == 59.0);
}

TEST_CASE("an anchor loses its set after the lifetime (plus fade while in flight)", "[shgraph]") {
  CoefficientAnchor a;
  a.set_new(uniform(1.0f), 0.0, 1, nullptr, 0.0);
  a.update(0.0, timing());
  CHECK(a.update(60.01, timing()));  // reported once, to the owner
  CHECK_FALSE(a.has_coefficients());
  CHECK_FALSE(a.update(60.02, timing()));

  CoefficientAnchor b;
  b.set_new(uniform(1.0f), 0.0, 1, nullptr, 0.0);
  b.prepare_for_new();
  CHECK_FALSE(b.update(60.9, timing()));
  CHECK(b.update(61.01, timing()));
}

TEST_CASE("New is held exactly while a fade runs, and a replacement mid-fade keeps fading to it",
          "[shgraph]") {
  CoefficientAnchor a;
  CHECK_FALSE(a.holds_new());
  const Sh9Rgb before = uniform(1.0f);
  a.set_new(uniform(3.0f), 10.0, 1, &before, 4.0);
  CHECK(a.holds_new());
  a.update(10.5, timing());  // the fade starts
  a.update(10.75, timing());
  CHECK(a.holds_new());
  // A second set arrives mid-fade: the fade goes on from where Active is, towards the new one.
  a.set_new(uniform(5.0f), 10.8, 2, nullptr, 0.0);
  CHECK(a.holds_new());
  CHECK(a.active().c[0].x == Approx(1.5f));
  a.update(10.9, timing());  // restarts: 1 s from here
  a.update(11.4, timing());
  CHECK(a.active().c[0].x == Approx(1.5f + 0.5f * (5.0f - 1.5f)));
  a.update(11.9, timing());
  CHECK(a.active() == uniform(5.0f));
  CHECK_FALSE(a.fading());
  CHECK_FALSE(a.holds_new());  // one set from here on
  // Expiry mid-fade drops New with the set.
  a.set_new(uniform(7.0f), 20.0, 3, nullptr, 0.0);
  CHECK(a.holds_new());
  CHECK(a.update(20.0 + 60.5, timing()));
  CHECK_FALSE(a.has_coefficients());
  CHECK_FALSE(a.holds_new());
}
