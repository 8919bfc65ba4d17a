#pragma once
// Settings of the metrics, parsed from a scenario's "metrics" object. All optional; the
// defaults are what SPEC section 5 asks for.
//
// JSON ("metrics" object):
//   normals           "axes6" | "axes26": the normals irradiance is compared at     ["axes6"]
//   exposure          >= 0, multiplier of linear irradiance before the tone map;
//                     0 = automatic: key / log-average luminance of the reference     [0]
//   exposure_key      (0, 1], Reinhard key for the automatic exposure                 [0.18]
//   pop_threshold_de  > 0, CIEDE2000 change that counts as a pop (1 = one JND)        [1.0]
//   pop_masking       0..1: the threshold rises to this fraction of the receiver's own
//                     true frame-to-frame jump (temporal masking, colour_pops.h);
//                     0 = a fixed threshold                                             [0.1]
//   rel_error_floor   > 0, irradiance units: denominator floor of the relative error  [1e-6]
//   accuracy_every    1..1000000: accuracy (error vs reference) on frames with
//                     frame % k == 0; pops, staleness, coverage and costs every frame  [1]
//   coverage          { min_spacing_m > 0 [4], spacing_per_m >= 0 [0.25] }
//   demand            { ring_radii_m [> 0, ...]   [5, 10, 20, 40, 80, 160],
//                       azimuths 1..360 per ring  [8],
//                       ahead_s [>= 0, ...]       [0.5, 1, 2, 4],
//                       height_m >= 0 above ground [1.5] }
//   response          { event_de > 0 [5], window_s (0, 60] [0.5], settled_de > 0 [2] }:
//                     a true change of more than event_de within window_s is an event; its
//                     response time lasts until the planner is within settled_de
//                     (response_time.h)
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include "sim/base/json_reader.h"
#include "sim/metrics/coverage.h"
#include "sim/metrics/response_time.h"

namespace ambisim {

struct MetricSettings {
  std::string normals_name = "axes6";
  std::vector<glm::dvec3> normals;  // normal_set(normals_name); filled by the parser/defaults()
  double exposure = 0.0;            // 0 = automatic (resolve with reference_exposure first)
  double exposure_key = 0.18;
  double pop_threshold_de = 1.0;
  double pop_masking = 0.1;
  double rel_error_floor = 1e-6;
  int accuracy_every = 1;
  CoverageRule coverage;
  DemandLayout demand;
  ResponseSettings response;

  // The defaults with `normals` filled in.
  static MetricSettings defaults();
};

// Reads the object (schema above) and calls r.finish().
MetricSettings parse_metric_settings(ObjectReader& r);

// Every setting, in the schema's key order, for the run's self-describing output. Reading it back
// with parse_metric_settings gives the same settings.
nlohmann::ordered_json metric_settings_to_json(const MetricSettings& s);

}  // namespace ambisim
