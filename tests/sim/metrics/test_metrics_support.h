#pragma once
// Shared helpers of the metrics tests: greys of a chosen displayed lightness, and a frame
// driver for RunMetrics.
#include <cmath>
#include <cstdint>
#include <vector>

#include "sim/colour/rgb.h"
#include "sim/metrics/metrics.h"

namespace ambisim::test {

inline constexpr double kFps = 60.0;  // the frame rate of the metrics tests

// The grey irradiance (v, v, v) whose displayed CIELAB lightness is L (8 < L < 100) at
// `exposure`: invert L* = 116 f(Y_d) - 16, then Reinhard Y_d = Y / (1 + Y), Y = v exposure.
// (A grey's luminance is v: the Y row of the sRGB matrix sums to 1.)
inline Rgb grey_of_lightness(double lightness, double exposure) {
  const double f = (lightness + 16.0) / 116.0;
  const double yd = f * f * f;
  return Rgb(static_cast<float>(yd / (1.0 - yd) / exposure));
}

// The same in double, for irradiance fades computed before rounding to float.
inline double grey_value_of_lightness(double lightness, double exposure) {
  const double f = (lightness + 16.0) / 116.0;
  const double yd = f * f * f;
  return yd / (1.0 - yd) / exposure;
}

// A lookup served by one probe at 1 m spacing, captured at `data_time`.
inline LookupResult served_lookup(double data_time = 0.0) {
  LookupResult r;
  r.contributor_count = 1;
  r.spacing_m = 1.0;
  r.data_time = data_time;
  return r;
}

// Settings with a fixed exposure of 1 and the six axes.
inline MetricSettings unit_settings() {
  MetricSettings s = MetricSettings::defaults();
  s.exposure = 1.0;
  return s;
}

// Feeds one receiver with the same planner / reference irradiance on every normal.
inline void feed(RunMetrics& m, std::uint64_t id, Rgb planner, Rgb reference,
                 const LookupResult& lookup = served_lookup()) {
  const std::size_t n = m.settings().normals.size();
  const std::vector<Rgb> p(n, planner);
  const std::vector<Rgb> r(n, reference);
  m.receiver(id, p, r, lookup);
}

}  // namespace ambisim::test
