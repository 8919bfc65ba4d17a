// The per-run accumulator: accuracy samples and percentiles, accuracy_every, coverage,
// staleness, costs, the JSON summary, CSV formatting and the settings record.
#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <vector>

#include "sim/metrics/accuracy.h"
#include "sim/metrics/metrics.h"
#include "test_metrics_support.h"

using namespace ambisim;
using ambisim::test::feed;
using ambisim::test::grey_of_lightness;
using ambisim::test::served_lookup;
using ambisim::test::unit_settings;

namespace {
constexpr double kRelTol = 1e-6;       // float irradiance inputs
constexpr double kMeanTol = 1e-12;     // dt-weighted means of exact values
constexpr double kStoredDeTol = 1e-5;  // float-stored dE00 samples

int count_cells(const std::string& line) {
  int n = 1;
  for (char c : line) n += c == ',';
  return n;
}
}  // namespace

TEST_CASE("accuracy samples, their mean, p95 and max", "[metrics]") {
  // Receiver 1 exact; receiver 2 at twice the reference (rel = 1) for 20 frames.
  const Rgb r = grey_of_lightness(50.0, 1.0);
  RunMetrics m(unit_settings());
  for (int f = 0; f < 20; ++f) {
    m.begin_frame(f, f * 0.01, 0.01);
    feed(m, 1, r, r);
    feed(m, 2, 2.0f * r, r);
    const FrameRow row = m.end_frame();
    CHECK(row.rel_mean == Approx(0.5).margin(kRelTol));
    CHECK(row.de2000_max == Approx(display_difference(2.0f * r, r, 1.0)).margin(1e-12));
  }
  const Summary s = m.summary();
  const double de = display_difference(2.0f * r, r, 1.0);
  CHECK(s.samples == 2 * 20 * 6);
  CHECK(s.rel.mean == Approx(0.5).margin(kRelTol));
  CHECK(s.rel.max == Approx(1.0).margin(kRelTol));
  // Half the samples are 0 and half are `de`: the 95th percentile is `de`.
  CHECK(s.rel.p95 == Approx(1.0).margin(kRelTol));
  CHECK(s.de2000.mean == Approx(de / 2).margin(1e-12));
  CHECK(s.de2000.p95 == Approx(de).margin(kStoredDeTol));
  CHECK(s.de2000.max == Approx(de).margin(1e-12));
}

TEST_CASE("accuracy_every thins accuracy but pops stay on consecutive frames", "[metrics]") {
  MetricSettings st = unit_settings();
  st.accuracy_every = 4;
  RunMetrics m(st);
  const Rgb a = grey_of_lightness(50.0, 1.0);
  const Rgb b = grey_of_lightness(60.0, 1.0);
  for (int f = 0; f < 16; ++f) {
    m.begin_frame(f, f / 60.0, 1.0 / 60.0);
    feed(m, 1, f >= 9 ? b : a, a);  // the step lands on frame 9, not a multiple of 4
    const FrameRow row = m.end_frame();
    CHECK(row.accuracy_evaluated == (f % 4 == 0));
    CHECK(std::isnan(row.de2000_mean) == (f % 4 != 0));
  }
  const Summary s = m.summary();
  CHECK(s.samples == 4 * 6);  // frames 0, 4, 8, 12
  CHECK(s.pops.count == 1);
}

TEST_CASE("coverage per frame, by kind, and its dt-weighted mean", "[metrics]") {
  RunMetrics m(unit_settings());
  LookupResult far;  // 30 m spacing: served at 120 m (needs 30), not at 10 m (needs 4)
  far.contributor_count = 2;
  far.spacing_m = 30.0;
  LookupResult fallback = served_lookup();
  fallback.fell_back = true;

  m.begin_frame(0, 0.0, 0.01);
  m.demand_point(far, 120.0, DemandKind::ring);      // served
  m.demand_point(far, 10.0, DemandKind::ring);       // too coarse
  m.demand_point(fallback, 1.0, DemandKind::ahead);  // fell back
  m.demand_point(far, 10.0, DemandKind::receiver);   // too coarse
  CHECK(m.end_frame().coverage == 0.25);

  m.begin_frame(1, 0.01, 0.1);
  m.demand_point(served_lookup(), 10.0, DemandKind::receiver);
  m.demand_point(served_lookup(), 10.0, DemandKind::ring);
  const FrameRow row = m.end_frame();
  CHECK(row.coverage == 1.0);
  CHECK(row.demand_points == 2);

  m.begin_frame(2, 0.11, 0.5);  // no demand points: not part of the mean
  CHECK(std::isnan(m.end_frame().coverage));

  const Summary s = m.summary();
  CHECK(s.coverage.mean == Approx((0.25 * 0.01 + 1.0 * 0.1) / 0.11).margin(kMeanTol));
  CHECK(s.coverage.receivers == Approx((0.0 * 0.01 + 1.0 * 0.1) / 0.11).margin(kMeanTol));
  CHECK(s.coverage.ground == Approx((1.0 / 3.0 * 0.01 + 1.0 * 0.1) / 0.11).margin(kMeanTol));
  CHECK(s.coverage.samples == 6);
}

TEST_CASE("staleness over lookups that did not fall back", "[metrics]") {
  RunMetrics m(unit_settings());
  const Rgb r(1.0f);
  LookupResult fallback = served_lookup(0.0);
  fallback.fell_back = true;
  m.begin_frame(0, 10.0, 0.1);
  feed(m, 1, r, r, served_lookup(9.5));  // 0.5 s old
  feed(m, 2, r, r, served_lookup(8.0));  // 2 s old
  feed(m, 3, r, r, fallback);            // excluded (would be 10 s)
  CHECK(m.end_frame().staleness_mean == Approx(1.25).margin(kMeanTol));
  const Summary s = m.summary();
  CHECK(s.staleness.mean == Approx(1.25).margin(kMeanTol));
  CHECK(s.staleness.max == Approx(2.0).margin(kMeanTol));
}

TEST_CASE("costs: sums, maxima and dt-weighted means", "[metrics]") {
  RunMetrics m(unit_settings());
  m.begin_frame(0, 0.0, 0.01);
  m.costs({6, 1, 1, 5, 2, 10, 1000});
  m.end_frame();
  m.begin_frame(1, 0.01, 0.1);
  m.costs({3, 3, 2, 0, 0, 30, 4000});
  CHECK_THROWS_AS(m.costs({}), std::logic_error);
  const FrameRow row = m.end_frame();
  CHECK(row.live_probes == 30);
  CHECK(row.faces_granted == 3);
  const Summary s = m.summary();
  CHECK(s.faces.requested == 9);
  CHECK(s.faces.granted == 4);
  CHECK(s.faces.used == 3);
  CHECK(s.faces.refused == 5);
  CHECK(s.captures_refused == 2);
  CHECK(s.probes.max_live == 30);
  CHECK(s.probes.mean_live == Approx((10 * 0.01 + 30 * 0.1) / 0.11).margin(kMeanTol));
  CHECK(s.memory.max_bytes == 4000);
  CHECK(s.memory.mean_bytes == Approx((1000 * 0.01 + 4000 * 0.1) / 0.11).margin(1e-9));
  CHECK(s.frames == 2);
  CHECK(s.duration_s == Approx(0.11).margin(kMeanTol));
}

TEST_CASE("run metrics reject misuse", "[metrics]") {
  CHECK_THROWS_AS(RunMetrics(MetricSettings::defaults()), std::invalid_argument);  // exposure 0
  RunMetrics m(unit_settings());
  const std::vector<Rgb> three(3, Rgb(1.0f));
  CHECK_THROWS_AS(m.receiver(1, three, three, served_lookup()), std::logic_error);  // no frame
  m.begin_frame(5, 0.0, 0.01);
  CHECK_THROWS_AS(m.receiver(1, three, three, served_lookup()), std::invalid_argument);
  m.end_frame();
  CHECK_THROWS_AS(m.begin_frame(5, 0.0, 0.01), std::logic_error);  // frames must increase
}

TEST_CASE("summary JSON: key order, nulls without data", "[metrics]") {
  RunMetrics m(unit_settings());
  m.begin_frame(0, 0.0, 0.01);
  m.end_frame();
  const nlohmann::ordered_json j = RunMetrics::to_json(m.summary());
  std::vector<std::string> keys;
  for (const auto& [k, v] : j.items()) keys.push_back(k);
  CHECK(keys == std::vector<std::string>{
                    "frames", "duration_s", "receiver_minutes", "viewed_receiver_minutes",
                    "receiver_frames", "samples", "error", "pops", "response", "coverage",
                    "staleness", "faces", "captures", "bake", "probes", "memory", "sample"});
  CHECK(j["error"]["viewed"]["de2000"]["p95"].is_null());
  CHECK(j["error"]["uniform"]["de2000"]["p95"].is_null());
  CHECK(j["pops"]["viewed"]["per_min"].is_null());
  CHECK(j["pops"]["uniform"]["per_min"].is_null());
  CHECK(j["pops"]["uniform"]["count"] == 0);
  CHECK(j["response"]["events"] == 0);
  CHECK(j["response"]["median_s"].is_null());
  CHECK(j["frames"] == 1);
  // Embeds in a plain nlohmann::json document.
  const nlohmann::json plain = j;
  CHECK(plain["error"]["uniform"]["rel"].contains("mean"));
}

TEST_CASE("CSV numbers are fixed and locale-independent", "[metrics]") {
  CHECK(format_number(0.1) == "0.1");
  CHECK(format_number(1.0) == "1");
  CHECK(format_number(1234567.0) == "1.23457e+06");
  CHECK(format_number(1e-5) == "1e-05");
  CHECK(format_number(-2.5) == "-2.5");
  CHECK(format_number(-0.0) == "0");
  CHECK(format_number(std::nan("")) == "nan");
  CHECK(format_number(std::int64_t{9007199254740993}) == "9007199254740993");

  FrameRow row;
  row.frame = 3;
  row.time = 0.05;
  row.dt = 1.0 / 60.0;
  row.de2000_mean = std::nan("");
  row.coverage = 0.75;
  row.accuracy_evaluated = true;
  const std::string line = frame_csv_row(row);
  CHECK(line.rfind("3,0.05,0.0166667,0,1,nan,", 0) == 0);
  CHECK(count_cells(line) == count_cells(frame_csv_header()));
  CHECK(count_cells(summary_csv_row(Summary{})) == count_cells(summary_csv_header()));
  CHECK(summary_csv_header().rfind("frames,duration_s,receiver_minutes,viewed_receiver_minutes,"
                                   "receiver_frames,samples,error.viewed.de2000.mean,"
                                   "error.viewed.de2000.p95,error.viewed.de2000.max,"
                                   "error.uniform.de2000.mean,",
                                   0) == 0);
}

TEST_CASE("metric settings: defaults, values, errors, round trip", "[metrics]") {
  {
    const nlohmann::json j = nlohmann::json::object();
    ObjectReader r(j, "s.json", "/metrics");
    const MetricSettings s = parse_metric_settings(r);
    CHECK(s.normals.size() == 6);
    CHECK(s.exposure == 0.0);
    CHECK(s.pop_threshold_de == 1.0);
    CHECK(s.coverage.min_spacing_m == 4.0);
    CHECK(s.demand.ring_radii_m.size() == 6);
  }
  const nlohmann::json j = nlohmann::json::parse(R"({
    "normals": "axes26", "exposure": 0.5, "pop_threshold_de": 2, "accuracy_every": 3,
    "coverage": {"min_spacing_m": 2, "spacing_per_m": 0.1},
    "demand": {"ring_radii_m": [10, 50], "azimuths": 4, "ahead_s": [], "height_m": 2}})");
  ObjectReader r(j, "s.json", "/metrics");
  const MetricSettings s = parse_metric_settings(r);
  CHECK(s.normals.size() == 26);
  CHECK(s.exposure == 0.5);
  CHECK(s.accuracy_every == 3);
  CHECK(s.coverage.spacing_per_m == 0.1);
  CHECK(s.demand.ring_radii_m == std::vector<double>{10, 50});
  CHECK(s.demand.ahead_s.empty());

  const nlohmann::json back = metric_settings_to_json(s);
  ObjectReader rb(back, "", "");
  const MetricSettings s2 = parse_metric_settings(rb);
  CHECK(metric_settings_to_json(s2) == metric_settings_to_json(s));

  const auto error_of = [](const char* text) {
    const nlohmann::json bad = nlohmann::json::parse(text);
    try {
      ObjectReader rr(bad, "s.json", "/metrics");
      parse_metric_settings(rr);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK_THAT(error_of(R"({"pop_treshold_de": 1})"),
             Catch::Contains("/metrics") && Catch::Contains("pop_treshold_de"));
  CHECK_THAT(error_of(R"({"normals": "axes8"})"), Catch::Contains("/metrics/normals"));
  CHECK_THAT(error_of(R"({"demand": {"ring_radii_m": [0]}})"),
             Catch::Contains("/metrics/demand/ring_radii_m"));
  CHECK_THAT(error_of(R"({"accuracy_every": 0})"), Catch::Contains("/metrics/accuracy_every"));
}
