#pragma once
// The per-run metrics accumulator (SPEC section 5): the simulator feeds it every frame, it
// returns one row of the per-frame series per frame and the run's summary at the end.
//
// Per frame, in this order:
//   begin_frame(frame, time, dt, cut) frames strictly increasing; dt > 0 is this frame's step
//   receiver(id, P, R, lookup, view) once per live receiver: planner and reference irradiance
//                                    at settings.normals (same order), its lookup, and how the
//                                    camera sees it (view_weights.h)
//   demand_point(lookup, d, kind)    once per coverage demand point, receivers included
//                                    (kind receiver) and the ground points of demand_points()
//   costs(c)                         at most once (absent = all zeros)
//   end_frame() -> FrameRow
//
// Definitions (see accuracy.h, colour_pops.h, coverage.h for the per-sample ones):
// - accuracy samples: one per receiver x normal on frames with frame % accuracy_every == 0.
//   error.uniform.* weigh every sample alike: mean, max, and the nearest-rank p95
//   (statistics.h). error.viewed.* weigh each sample by what the player sees: the receiver's
//   screen weight (solid angle, 0 outside the view) times the normal's visible share; mean =
//   weighted mean, p95 = weighted nearest-rank percentile, max over samples of positive weight.
//   Percentiles are exact order statistics of the samples stored as float (relative rounding
//   6e-8, far below the 6 digits reported; float halves the memory of a long run); means and
//   maxima are accumulated in double.
// - pops (colour_pops.h): evaluated on every frame whatever accuracy_every is, because they
//   need consecutive frames (the reference must therefore be passed every frame).
//   pops.uniform: count = receiver-frames whose unexplained change (largest over all normals)
//   exceeds pop_threshold_de; sum = the sum of those changes; max = the largest unexplained
//   change of any receiver-frame (pop or not); per_min = count / receiver_minutes, with
//   receiver_minutes = sum over frames of (live receivers x dt) / 60.
//   pops.viewed: a receiver-frame of weight w > 0 pops when its unexplained change over the
//   normals the camera sees exceeds the threshold; sum = the sum of the weights w of those
//   pops (sr); per_min = sum / viewed_receiver_minutes, with viewed_receiver_minutes = sum over
//   frames and receivers of w x dt / 60 (weights summed over time), so it counts pops per minute
//   of looking at receivers; max = the largest seen unexplained change of a receiver-frame of
//   positive weight.
// - response (response_time.h): true-change events, and the median and p95 of the time the
//   planner took to come back within settled_de of the truth, every frame.
// - coverage: per frame, the share of demand points served; coverage.mean is its dt-weighted
//   mean over frames that had demand points (a 10 fps stretch weighs per frame ten times a
//   100 fps one, so the number is a share of time); coverage.receivers / .ground the same over
//   receiver / ring+ahead points only.
// - staleness: time - data_time of receiver lookups that did not fall back (a fallback holds
//   no probe data), mean and max over receiver-frames.
// - costs: faces and refusals summed over frames; probes.max_live and memory.max_bytes are
//   maxima; probes.mean_live and memory.mean_bytes dt-weighted means.
// Quantities without data are NaN in the structs, null in JSON and "nan" in CSV.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include "sim/base/statistics.h"
#include "sim/colour/rgb.h"
#include "sim/metrics/colour_pops.h"
#include "sim/metrics/coverage.h"
#include "sim/metrics/metric_settings.h"
#include "sim/metrics/response_time.h"
#include "sim/metrics/sample_interval.h"
#include "sim/planner.h"

namespace ambisim {

// How the camera sees one receiver this frame (view_weights.h).
struct ReceiverViewing {
  double weight = 0.0;                  // screen solid angle (sr); 0: not seen
  glm::dvec3 to_camera{0.0, 0.0, 1.0};  // unit direction from the receiver to the camera
};

// Per-frame costs as the simulator counts them (all >= 0).
struct FrameCosts {
  std::int64_t faces_requested = 0;   // cube faces the planner asked for this frame
  std::int64_t faces_granted = 0;     // faces the budget granted (rendered)
  std::int64_t faces_used = 0;        // granted faces that ended up in a delivered probe
  std::int64_t faces_refused = 0;     // requested - granted
  std::int64_t captures_refused = 0;  // capture requests refused (Planner::refused calls)
  std::int64_t live_probes = 0;       // PlannerStats::live_probes
  std::int64_t bytes = 0;             // PlannerStats::bytes
};

// What the planner captured before the first frame, outside the budget (Planner::preload).
struct BakeCosts {
  std::int64_t captures = 0;
  std::int64_t faces = 0;
};

// One row of the per-frame series.
struct FrameRow {
  std::int64_t frame = 0;
  double time = 0.0;  // s
  double dt = 0.0;    // s
  std::int64_t receivers = 0;
  bool accuracy_evaluated = false;  // frame % accuracy_every == 0
  double de2000_mean = 0.0;         // over this frame's samples (NaN if none)
  double de2000_max = 0.0;
  double rel_mean = 0.0;
  double de2000_viewed_mean = 0.0;  // weighted as error.viewed (NaN if nothing is seen)
  std::int64_t pops = 0;            // uniform: receiver-frames that popped
  std::int64_t viewed_pops = 0;     // receivers of positive weight that popped where seen
  double change_max = 0.0;          // largest unexplained change this frame (NaN if none)
  double view_weight = 0.0;         // sum of the receivers' screen weights (sr)
  std::int64_t demand_points = 0;
  double coverage = 0.0;  // share served (NaN without demand points)
  double staleness_mean = 0.0;
  std::int64_t live_probes = 0;
  std::int64_t bytes = 0;
  std::int64_t faces_granted = 0;
  std::int64_t faces_used = 0;
};

struct ErrorSummary {
  double mean = 0.0;
  double p95 = 0.0;
  double max = 0.0;
};

struct PopSummary {
  double per_min = 0.0;
  double max = 0.0;
  double sum = 0.0;
  std::int64_t count = 0;  // uniform: pops; viewed: receiver-frames that popped where seen
};

struct Summary {
  std::int64_t frames = 0;
  double duration_s = 0.0;  // sum of dt
  double receiver_minutes = 0.0;
  double viewed_receiver_minutes = 0.0;  // sum of screen weight x dt / 60 (sr min)
  std::int64_t receiver_frames = 0;
  std::int64_t samples = 0;  // accuracy samples
  ErrorSummary de2000_viewed;
  ErrorSummary de2000;  // uniform
  ErrorSummary rel;     // uniform
  PopSummary pops_viewed;
  PopSummary pops;  // uniform
  ResponseSummary response;
  struct {
    double mean = 0.0;
    double receivers = 0.0;
    double ground = 0.0;
    std::int64_t samples = 0;  // demand-point lookups
  } coverage;
  struct {
    double mean = 0.0;  // s
    double max = 0.0;
  } staleness;
  struct {
    std::int64_t requested = 0;
    std::int64_t granted = 0;
    std::int64_t used = 0;
    std::int64_t refused = 0;
  } faces;
  std::int64_t captures_refused = 0;
  BakeCosts bake;
  struct {
    std::int64_t max_live = 0;
    double mean_live = 0.0;
  } probes;
  struct {
    std::int64_t max_bytes = 0;
    double mean_bytes = 0.0;
  } memory;
  // The receivers scored (a game's load: every stride-th of each kind; 1 = all of them), how
  // many the planner lit, and the 95% intervals of the scores from the sample (NaN when every
  // receiver is scored: the scores are then exact).
  struct {
    std::int64_t stride = 1;
    std::int64_t receivers_scored = 0;
    std::int64_t receivers_lit = 0;
    SampleIntervals ci95;
  } sample;
};

class RunMetrics {
 public:
  // settings.exposure must already be resolved (> 0): see reference_exposure().
  // Throws std::invalid_argument otherwise, or without normals.
  explicit RunMetrics(MetricSettings settings);

  // camera_cut: the camera teleported this frame; no receiver can pop across it.
  void begin_frame(std::int64_t frame, double time, double dt, bool camera_cut = false);
  // Throws std::invalid_argument unless both spans hold one value per normal. A receiver given
  // no view weighs 0 in the viewed metrics. Returns the receiver's pop evaluation (for tools
  // that show where the pops were, e.g. `ambisim film`; scoring does not need it).
  // `stratum`: the receiver's stratum in a sampled referee (its kind), for the intervals.
  PopEvaluation receiver(std::uint64_t id, std::span<const Rgb> planner_e,
                         std::span<const Rgb> reference_e, const LookupResult& lookup,
                         const ReceiverViewing& view = {}, int stratum = 0);
  // A sampled referee: every `stride`-th receiver is scored, of `receivers_lit` the planner
  // lit (summary().sample). Call any time before summary().
  void set_sample(std::int64_t stride, std::int64_t receivers_lit) {
    sample_stride_ = stride;
    receivers_lit_ = receivers_lit;
  }
  void demand_point(const LookupResult& lookup, double distance_to_camera_m, DemandKind kind);
  void costs(const FrameCosts& c);
  // The preload's cost, once, before or in the first frame.
  void bake(const BakeCosts& b) { bake_ = b; }
  FrameRow end_frame();

  bool accuracy_frame(std::int64_t frame) const { return frame % settings_.accuracy_every == 0; }
  const MetricSettings& settings() const { return settings_; }
  Summary summary() const;

  // Key order: frames, duration_s, receiver_minutes, viewed_receiver_minutes, receiver_frames,
  // samples, error{viewed{de2000{mean,p95,max}}, uniform{de2000{...}, rel{...}}},
  // pops{viewed{per_min,max,sum,count}, uniform{per_min,max,sum,count}},
  // response{events,censored,median_s,p95_s}, coverage{mean,receivers,ground,samples},
  // staleness{mean,max},
  // faces{requested,granted,used,refused}, captures{refused}, bake{captures,faces},
  // probes{max_live,mean_live},
  // memory{max_bytes,mean_bytes},
  // sample{stride,receivers_scored,receivers_lit,ci95{de2000_viewed_mean{low,high},
  // de2000_mean{low,high},pops_viewed_per_min{low,high},pops_per_min{low,high}}}. Non-finite values
  // are written as null.
  static nlohmann::ordered_json to_json(const Summary& s);

 private:
  void require_frame(const char* what) const;

  MetricSettings settings_;
  PopTracker pops_;
  ResponseTracker response_;
  bool in_frame_ = false;
  bool have_frame_ = false;
  FrameRow row_;
  std::vector<Lab> planner_lab_;
  std::vector<Lab> reference_lab_;
  std::vector<double> share_;  // visible share per normal, this receiver

  // This frame.
  RunningStats frame_de_, frame_rel_, frame_change_, frame_stale_;
  TimeWeightedMean frame_de_viewed_;
  std::int64_t frame_served_[3] = {0, 0, 0};  // by DemandKind
  std::int64_t frame_demand_[3] = {0, 0, 0};
  bool frame_costs_given_ = false;

  // The run.
  std::int64_t frames_ = 0;
  double duration_s_ = 0.0;
  double receiver_seconds_ = 0.0;
  std::int64_t receiver_frames_ = 0;
  RunningStats de_, rel_, change_, stale_;
  std::vector<float> de_samples_, rel_samples_;
  std::int64_t pop_count_ = 0;
  double pop_sum_ = 0.0;
  TimeWeightedMean de_viewed_;
  RunningStats de_viewed_max_, change_viewed_;
  std::vector<WeightedSample> de_viewed_samples_;
  double viewed_seconds_ = 0.0;  // sum of weight x dt
  double viewed_pop_weight_ = 0.0;
  std::int64_t viewed_pop_count_ = 0;
  TimeWeightedMean coverage_all_, coverage_receivers_, coverage_ground_;
  std::int64_t demand_samples_ = 0;
  FrameCosts cost_sums_;
  BakeCosts bake_;
  std::int64_t max_live_ = 0;
  std::int64_t max_bytes_ = 0;
  TimeWeightedMean live_mean_, bytes_mean_;
  ReceiverTally tally_;
  std::int64_t sample_stride_ = 1;
  std::int64_t receivers_lit_ = 0;
};

// Fixed, locale-independent number text for CSV: shortest "%.6g" equivalent via std::to_chars
// (6 significant digits), "nan"/"inf"/"-inf" for non-finite values, -0 written as 0.
std::string format_number(double x);
std::string format_number(std::int64_t x);

// The per-frame CSV: header (no trailing newline) and one row, same columns:
// frame,time,dt,receivers,accuracy,de2000_mean,de2000_max,rel_mean,de2000_viewed_mean,pops,
// viewed_pops,change_max,view_weight,demand_points,coverage,staleness_mean,live_probes,bytes,
// faces_granted,faces_used
std::string frame_csv_header();
std::string frame_csv_row(const FrameRow& row);

// The summary as one CSV row for sweeps; column names are the JSON paths joined with '.'
// (error.viewed.de2000.mean, ..., memory.mean_bytes), in to_json's order.
std::string summary_csv_header();
std::string summary_csv_row(const Summary& s);

}  // namespace ambisim
