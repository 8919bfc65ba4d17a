// The viewed metrics: error and pops weighted by what the player sees (SPEC section 5).
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "sim/colour/ciede2000.h"
#include "sim/colour/tone_map.h"
#include "sim/metrics/metrics.h"
#include "test_metrics_support.h"

using namespace ambisim;
using ambisim::test::grey_of_lightness;
using ambisim::test::kFps;
using ambisim::test::served_lookup;
using ambisim::test::unit_settings;

namespace {

constexpr double kGreyDeTol = 1e-3;  // dE00 of float greys (L round-trips to ~1e-4)

// axes6 order: +x, -x, +y, -y, +z, -z.
constexpr std::size_t kUp = 4, kDown = 5;

// One value per normal: `base` everywhere, `at` on normal k.
std::vector<Rgb> greys(double base, std::size_t k, double at) {
  std::vector<Rgb> v(6, grey_of_lightness(base, 1.0));
  v[k] = grey_of_lightness(at, 1.0);
  return v;
}

double grey_de00(double a, double b) { return ciede2000(Lab{a, 0, 0}, Lab{b, 0, 0}); }

const ReceiverViewing kFromAbove{1e-3, {0.0, 0.0, 1.0}};  // seen from straight above

}  // namespace

TEST_CASE("viewed error weighs the normals the camera sees, uniform error all", "[metrics]") {
  RunMetrics m(unit_settings());
  m.begin_frame(0, 0.0, 1.0 / kFps);
  const std::vector<Rgb> truth(6, grey_of_lightness(50.0, 1.0));
  // Wrong by 10 L on the down normal only: invisible from above.
  m.receiver(1, greys(50, kDown, 60), truth, served_lookup(), kFromAbove);
  m.end_frame();
  const Summary s = m.summary();
  CHECK(s.de2000.max == Approx(grey_de00(50, 60)).margin(kGreyDeTol));
  CHECK(s.de2000.mean == Approx(grey_de00(50, 60) / 6.0).margin(kGreyDeTol));
  CHECK(s.de2000_viewed.mean == Approx(0.0).margin(kGreyDeTol));
  CHECK(s.de2000_viewed.max == Approx(0.0).margin(kGreyDeTol));

  // The same error on the up normal is all that the viewed metrics see.
  RunMetrics up(unit_settings());
  up.begin_frame(0, 0.0, 1.0 / kFps);
  up.receiver(1, greys(50, kUp, 60), truth, served_lookup(), kFromAbove);
  up.end_frame();
  CHECK(up.summary().de2000_viewed.mean == Approx(grey_de00(50, 60)).margin(kGreyDeTol));
  CHECK(up.summary().de2000_viewed.p95 == Approx(grey_de00(50, 60)).margin(kGreyDeTol));
}

TEST_CASE("viewed error weighs receivers by their screen weight", "[metrics]") {
  RunMetrics m(unit_settings());
  m.begin_frame(0, 0.0, 1.0 / kFps);
  const std::vector<Rgb> truth(6, grey_of_lightness(50.0, 1.0));
  const std::vector<Rgb> wrong(6, grey_of_lightness(60.0, 1.0));
  // Receiver 1 weighs three times receiver 2; receiver 3 is not seen at all (weight 0).
  m.receiver(1, truth, truth, served_lookup(), {3e-3, {0, 0, 1}});
  m.receiver(2, wrong, truth, served_lookup(), {1e-3, {0, 0, 1}});
  m.receiver(3, wrong, truth, served_lookup(), {});
  m.end_frame();
  const Summary s = m.summary();
  CHECK(s.de2000_viewed.mean == Approx(grey_de00(50, 60) / 4.0).margin(kGreyDeTol));
  // The weighted p95: receiver 2 holds a quarter of the weight, above the 5 % tail.
  CHECK(s.de2000_viewed.p95 == Approx(grey_de00(50, 60)).margin(kGreyDeTol));
  CHECK(s.de2000.mean == Approx(grey_de00(50, 60) * 2.0 / 3.0).margin(kGreyDeTol));
  CHECK(s.viewed_receiver_minutes == Approx(4e-3 / kFps / 60.0).epsilon(1e-12));
}

TEST_CASE("a pop on a normal the camera cannot see is no viewed pop", "[metrics]") {
  const std::vector<Rgb> truth(6, grey_of_lightness(50.0, 1.0));
  for (std::size_t k : {kDown, kUp}) {
    RunMetrics m(unit_settings());
    for (int f = 0; f < 20; ++f) {
      m.begin_frame(f, f / kFps, 1.0 / kFps);
      m.receiver(1, f < 10 ? truth : greys(50, k, 60), truth, served_lookup(), kFromAbove);
      m.end_frame();
    }
    const Summary s = m.summary();
    CAPTURE(k);
    CHECK(s.pops.count == 1);  // uniform: every normal counts
    CHECK(s.pops_viewed.count == (k == kUp ? 1 : 0));
    const double minutes = 20.0 * kFromAbove.weight / kFps / 60.0;
    CHECK(s.viewed_receiver_minutes == Approx(minutes).epsilon(1e-12));
    CHECK(s.pops_viewed.per_min ==
          Approx((k == kUp ? kFromAbove.weight : 0.0) / minutes).epsilon(1e-12));
    CHECK(s.pops_viewed.sum == Approx(k == kUp ? kFromAbove.weight : 0.0).epsilon(1e-12));
  }
}

TEST_CASE("viewed pops count per viewed receiver-minute: unseen receivers never pop", "[metrics]") {
  const std::vector<Rgb> a(6, grey_of_lightness(50.0, 1.0));
  const std::vector<Rgb> b(6, grey_of_lightness(60.0, 1.0));
  RunMetrics m(unit_settings());
  for (int f = 0; f < 120; ++f) {
    m.begin_frame(f, f / kFps, 1.0 / kFps);
    // Receiver 1 (weight 2w) pops at 30; receiver 2 (weight w) at 60; receiver 3 (unseen) at 90.
    m.receiver(1, f < 30 ? a : b, a, served_lookup(), {2e-3, {0, 0, 1}});
    m.receiver(2, f < 60 ? a : b, a, served_lookup(), {1e-3, {0, 0, 1}});
    m.receiver(3, f < 90 ? a : b, a, served_lookup(), {});
    m.end_frame();
  }
  const Summary s = m.summary();
  CHECK(s.pops.count == 3);
  CHECK(s.pops_viewed.count == 2);
  const double viewed_minutes = 120.0 * 3e-3 / kFps / 60.0;
  CHECK(s.pops_viewed.per_min == Approx(3e-3 / viewed_minutes).epsilon(1e-12));
  CHECK(s.pops_viewed.max == Approx(grey_de00(50, 60)).margin(kGreyDeTol));
}
