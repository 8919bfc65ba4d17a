#include "sim/metrics/metric_settings.h"

#include "sim/metrics/accuracy.h"

namespace ambisim {

MetricSettings MetricSettings::defaults() {
  MetricSettings s;
  s.normals = normal_set(s.normals_name);
  return s;
}

namespace {

CoverageRule parse_coverage(ObjectReader& r) {
  CoverageRule c;
  c.min_spacing_m = r.number("min_spacing_m", c.min_spacing_m, Range::positive());
  c.spacing_per_m = r.number("spacing_per_m", c.spacing_per_m, Range::closed(0.0, 100.0));
  r.finish();
  return c;
}

DemandLayout parse_demand(ObjectReader& r) {
  DemandLayout d;
  if (r.has("ring_radii_m")) d.ring_radii_m = r.numbers("ring_radii_m", {0.0, 1e7, true, false});
  d.azimuths = r.integer("azimuths", d.azimuths, Range::closed(1, 360));
  if (r.has("ahead_s")) d.ahead_s = r.numbers("ahead_s", Range::closed(0.0, 3600.0));
  d.height_m = r.number("height_m", d.height_m, Range::closed(0.0, 1e4));
  r.finish();
  return d;
}

ResponseSettings parse_response(ObjectReader& r) {
  ResponseSettings s;
  s.event_de = r.number("event_de", s.event_de, Range::positive());
  s.window_s = r.number("window_s", s.window_s, {0.0, 60.0, false, true});
  s.settled_de = r.number("settled_de", s.settled_de, Range::positive());
  r.finish();
  return s;
}

}  // namespace

MetricSettings parse_metric_settings(ObjectReader& r) {
  MetricSettings s = MetricSettings::defaults();
  s.normals_name = r.choice("normals", s.normals_name, {"axes6", "axes26"});
  s.normals = normal_set(s.normals_name);
  s.exposure = r.number("exposure", s.exposure, Range::non_negative());
  s.exposure_key = r.number("exposure_key", s.exposure_key, {0.0, 1.0, true, false});
  s.pop_threshold_de = r.number("pop_threshold_de", s.pop_threshold_de, Range::positive());
  s.pop_masking = r.number("pop_masking", s.pop_masking, Range::unit());
  s.rel_error_floor = r.number("rel_error_floor", s.rel_error_floor, Range::positive());
  s.accuracy_every = r.integer("accuracy_every", s.accuracy_every, Range::closed(1, 1e6));
  if (auto c = r.optional_object("coverage")) s.coverage = parse_coverage(*c);
  if (auto d = r.optional_object("demand")) s.demand = parse_demand(*d);
  if (auto p = r.optional_object("response")) s.response = parse_response(*p);
  r.finish();
  return s;
}

nlohmann::ordered_json metric_settings_to_json(const MetricSettings& s) {
  nlohmann::ordered_json j;
  j["normals"] = s.normals_name;
  j["exposure"] = s.exposure;
  j["exposure_key"] = s.exposure_key;
  j["pop_threshold_de"] = s.pop_threshold_de;
  j["pop_masking"] = s.pop_masking;
  j["rel_error_floor"] = s.rel_error_floor;
  j["accuracy_every"] = s.accuracy_every;
  j["coverage"] = {{"min_spacing_m", s.coverage.min_spacing_m},
                   {"spacing_per_m", s.coverage.spacing_per_m}};
  j["demand"] = {{"ring_radii_m", s.demand.ring_radii_m},
                 {"azimuths", s.demand.azimuths},
                 {"ahead_s", s.demand.ahead_s},
                 {"height_m", s.demand.height_m}};
  j["response"] = {{"event_de", s.response.event_de},
                   {"window_s", s.response.window_s},
                   {"settled_de", s.response.settled_de}};
  return j;
}

}  // namespace ambisim
