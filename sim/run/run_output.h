#pragma once
// The self-describing output of one run: DIR/result.json (format version, scenario name and
// hashes, seeds, planner and parameters, exposure, summary, per-frame series) and
// DIR/frames.csv. Measured timings go in result.json's separate "timing" section; everything
// else is deterministic (byte-identical for the same inputs).
#include <string>

#include <nlohmann/json.hpp>

#include "sim/base/output_file.h"
#include "sim/run/simulator.h"
#include "sim/scenario/scenario.h"

namespace ambisim {

// 2: summary keys error.{viewed,uniform}.*, pops.{viewed,uniform}.*, response.*; series and
// frames.csv gain de2000_viewed_mean, viewed_pops and view_weight.
inline constexpr int kResultFormatVersion = 2;
// The results' model: bump it whenever the same inputs give different results (the reference,
// a metric, a planner's behaviour), so that `sweep --resume` recomputes runs instead of mixing
// old and new numbers. 2: the reference stops refining where interpolation predicts well.
// 3: planners without data answer the default ambient instead of black.
// 4: the ambisim planner's spacing and fades (forest_edge/flyover files changed themselves).
// 5: ambisim ranks objects by need alone and stores fp16 by default.
// 6: pops count only what the truth does not explain; viewed metrics; response time.
// 7: lighting that changes (the world in time, the refresh rules, the lamp layer; baked bakes
//    the objects' squares at its own face size).
inline constexpr int kResultsModelVersion = 7;

struct RunIdentity {
  std::string planner;
  nlohmann::json planner_params;
  nlohmann::json run = nullptr;  // sweep context (run id, hash, swept values); null for `run`
};

// The deterministic part of result.json (no timing).
nlohmann::ordered_json result_json(const Scenario& scenario, const RunIdentity& id,
                                   const RunResult& result);

// Writes DIR/result.json (with the timing section appended), DIR/frames.csv and DIR/views.json,
// creating DIR
// if needed. Refuses to overwrite either file unless overwrite is allow; files are written
// atomically, so an interrupted run leaves no partial result.
void write_run_output(const std::string& dir, const Scenario& scenario, const RunIdentity& id,
                      const RunResult& result, Overwrite overwrite);

std::string frames_csv(const RunResult& result);
// DIR/views.json: camera path and snapshots of the planner's nodes and the receivers.
std::string views_json(const RunResult& result);

}  // namespace ambisim
