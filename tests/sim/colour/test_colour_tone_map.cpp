// Reinhard tone map, exposure choice and the displayed colour (Lab, 8-bit sRGB).
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "sim/colour/ciede2000.h"
#include "sim/colour/tone_map.h"

using ambisim::Rgb;

namespace {
// tone_map_reinhard returns float: one float rounding on values <= 1. Measured: 1.4e-8.
constexpr double kToneFloatTol = 1e-6;
// display_lab is all double: closed-form Lab within double rounding. Measured: 0.
constexpr double kDisplayLabTol = 1e-9;
// Log-average luminance: closed forms up to exp/log rounding.
constexpr double kLogAvgRelTol = 1e-12;

float max3(Rgb c) { return std::max({c.x, c.y, c.z}); }
}  // namespace

TEST_CASE("Reinhard: black stays black, grey x maps to x / (1 + x)", "[colour]") {
  CHECK(ambisim::tone_map_reinhard(Rgb(0.0f), 1.0) == Rgb(0.0f));
  CHECK(ambisim::tone_map_reinhard(Rgb(0.7f), 0.0) == Rgb(0.0f));
  for (double x : {1e-4, 0.01, 0.18, 0.5, 1.0, 3.0, 100.0, 1e5}) {
    const Rgb out = ambisim::tone_map_reinhard(Rgb(float(x)), 1.0);
    for (int c = 0; c < 3; ++c) CHECK(out[c] == Approx(x / (1.0 + x)).margin(kToneFloatTol));
  }
  // Exposure is a plain multiplier in front of the curve.
  const Rgb out = ambisim::tone_map_reinhard(Rgb(0.25f), 4.0);
  CHECK(out.y == Approx(0.5).margin(kToneFloatTol));
}

TEST_CASE("Reinhard is monotone and stays in [0, 1]", "[colour]") {
  const std::vector<Rgb> colours = {Rgb(1, 1, 1),       Rgb(1, 0, 0), Rgb(0, 1, 0),
                                    Rgb(0, 0, 1),       Rgb(4, 1, 0), Rgb(0.2f, 0.5f, 0.9f),
                                    Rgb(0.05f, 3, 0.4f)};
  for (const Rgb& c : colours) {
    Rgb prev(0.0f);
    for (double k = 1e-3; k < 1e4; k *= 1.5) {
      const Rgb out = ambisim::tone_map_reinhard(c, k);
      for (int ch = 0; ch < 3; ++ch) {
        CHECK(out[ch] >= prev[ch]);
        CHECK(out[ch] >= 0.0f);
        CHECK(out[ch] <= 1.0f);
      }
      prev = out;
    }
  }
  // Negative components (SH ringing) are treated as 0.
  CHECK(ambisim::tone_map_reinhard(Rgb(-1.0f, 0.5f, -2.0f), 1.0) ==
        ambisim::tone_map_reinhard(Rgb(0.0f, 0.5f, 0.0f), 1.0));
}

TEST_CASE("Reinhard keeps hue: channel ratios survive, even past the gamut clip", "[colour]") {
  // A saturated orange and a pure blue bright enough that the blue channel would exceed 1
  // (blue has Y = 0.072 per unit) are both only scaled, never shifted in hue.
  for (const Rgb& c : {Rgb(4, 1, 0), Rgb(0, 0, 50), Rgb(0.3f, 0.6f, 0.1f), Rgb(20, 2, 9)}) {
    const Rgb out = ambisim::tone_map_reinhard(c, 1.0);
    const Rgb ratio_in = c / max3(c), ratio_out = out / max3(out);
    for (int ch = 0; ch < 3; ++ch)
      CHECK(ratio_out[ch] == Approx(ratio_in[ch]).margin(kToneFloatTol));
  }
  // Per-channel Reinhard would give (0.8, 0.5, 0) for (4, 1, 0); here green stays at 1/4 of red.
  const Rgb orange = ambisim::tone_map_reinhard(Rgb(4, 1, 0), 1.0);
  CHECK(orange.y / orange.x == Approx(0.25).margin(kToneFloatTol));
}

TEST_CASE("display_lab: closed form for greys, equal inputs give dE 0", "[colour]") {
  for (double x : {0.01, 0.18, 1.0, 10.0}) {
    const double t = x / (1.0 + x);
    const ambisim::Lab lab = ambisim::display_lab(Rgb(float(x)), 1.0);
    const double xf = double(float(x));  // the input is float
    const double tf = xf / (1.0 + xf);
    CHECK(t == Approx(tf).margin(1e-7));
    CHECK(lab.L == Approx(116.0 * std::cbrt(tf) - 16.0).margin(kDisplayLabTol));
    CHECK(lab.a == Approx(0.0).margin(kDisplayLabTol));
    CHECK(lab.b == Approx(0.0).margin(kDisplayLabTol));
  }
  const Rgb c(0.3f, 2.0f, 0.7f);
  CHECK(ambisim::ciede2000(ambisim::display_lab(c, 0.8), ambisim::display_lab(c, 0.8)) == 0.0);
  // A just-visible change stays visible after the tone map (a sanity check, not an oracle).
  CHECK(ambisim::ciede2000(ambisim::display_lab(c, 0.8), ambisim::display_lab(c * 1.2f, 0.8)) >
        1.0);
}

TEST_CASE("to_srgb8 encodes the tone-mapped colour", "[colour]") {
  // Grey 1 -> 0.5 displayed -> 188; grey 0.18/0.82 -> 0.18 displayed -> 118.
  CHECK(ambisim::to_srgb8(Rgb(1.0f), 1.0) == std::array<std::uint8_t, 3>{188, 188, 188});
  CHECK(ambisim::to_srgb8(Rgb(0.18f / 0.82f), 1.0) == std::array<std::uint8_t, 3>{118, 118, 118});
  CHECK(ambisim::to_srgb8(Rgb(0.0f), 1.0) == std::array<std::uint8_t, 3>{0, 0, 0});
  // Very bright pure red saturates to (255, 0, 0), hue intact.
  CHECK(ambisim::to_srgb8(Rgb(1e6f, 0, 0), 1.0) == std::array<std::uint8_t, 3>{255, 0, 0});
}

TEST_CASE("exposure from the key value and the log-average luminance", "[colour]") {
  // Geometric mean of luminances with delta = 0: sqrt(0.02 * 2) = 0.2.
  const std::vector<Rgb> scene = {Rgb(0.02f), Rgb(2.0f)};
  const double expect = std::sqrt(double(0.02f) * double(2.0f));
  CHECK(ambisim::log_average_luminance(scene, 0.0) == Approx(expect).epsilon(kLogAvgRelTol));
  // Black samples stay finite through delta.
  const std::vector<Rgb> dark = {Rgb(0.0f), Rgb(0.0f)};
  CHECK(ambisim::log_average_luminance(dark, 1e-4) == Approx(1e-4).epsilon(kLogAvgRelTol));
  CHECK(ambisim::log_average_luminance({}, 1e-4) == 0.0);
  // The log-average grey is displayed as the key: 0.18 -> 0.18 / 1.18 after Reinhard.
  const double e = ambisim::exposure_for_key(expect);
  CHECK(e == Approx(0.18 / expect).epsilon(kLogAvgRelTol));
  CHECK(ambisim::tone_map_reinhard(Rgb(float(expect)), e).y ==
        Approx(0.18 / 1.18).margin(kToneFloatTol));
}
