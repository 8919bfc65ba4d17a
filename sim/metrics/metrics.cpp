#include "sim/metrics/metrics.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "sim/colour/tone_map.h"
#include "sim/metrics/accuracy.h"
#include "sim/metrics/view_weights.h"

namespace ambisim {
namespace {

int kind_index(DemandKind kind) { return static_cast<int>(kind); }

double share(std::int64_t served, std::int64_t total) {
  return static_cast<double>(served) / static_cast<double>(total);
}

nlohmann::ordered_json number_or_null(double x) {
  return std::isfinite(x) ? nlohmann::ordered_json(x) : nlohmann::ordered_json(nullptr);
}

// Depth-first over an object, joining keys with '.'; leaves in document order.
void flatten(const nlohmann::ordered_json& j, const std::string& prefix,
             std::vector<std::pair<std::string, std::string>>& out) {
  for (const auto& [key, value] : j.items()) {
    const std::string name = prefix.empty() ? key : prefix + "." + key;
    if (value.is_object()) {
      flatten(value, name, out);
    } else if (value.is_number_integer()) {
      out.emplace_back(name, format_number(value.get<std::int64_t>()));
    } else if (value.is_number()) {
      out.emplace_back(name, format_number(value.get<double>()));
    } else {
      out.emplace_back(name, format_number(std::nan("")));  // null: no data
    }
  }
}

std::string join(const std::vector<std::string>& cells) {
  std::string s;
  for (std::size_t k = 0; k < cells.size(); ++k) {
    if (k > 0) s += ',';
    s += cells[k];
  }
  return s;
}

}  // namespace

RunMetrics::RunMetrics(MetricSettings settings)
    : settings_(std::move(settings)),
      pops_(settings_.pop_threshold_de, settings_.pop_masking),
      response_(settings_.response) {
  if (!(settings_.exposure > 0.0) || !std::isfinite(settings_.exposure)) {
    throw std::invalid_argument(
        "metrics: exposure must be resolved to a finite value > 0 (see reference_exposure)");
  }
  if (settings_.normals.empty()) throw std::invalid_argument("metrics: no normals");
  if (settings_.accuracy_every < 1) throw std::invalid_argument("metrics: accuracy_every < 1");
  planner_lab_.resize(settings_.normals.size());
  reference_lab_.resize(settings_.normals.size());
  share_.resize(settings_.normals.size());
}

void RunMetrics::require_frame(const char* what) const {
  if (!in_frame_) throw std::logic_error(std::string("metrics: ") + what + " outside a frame");
}

void RunMetrics::begin_frame(std::int64_t frame, double time, double dt, bool camera_cut) {
  if (in_frame_) throw std::logic_error("metrics: begin_frame before end_frame");
  if (have_frame_ && frame <= row_.frame) {
    throw std::logic_error("metrics: frame numbers must increase");
  }
  if (!(dt >= 0.0) || !std::isfinite(dt)) throw std::invalid_argument("metrics: dt must be >= 0");
  in_frame_ = true;
  have_frame_ = true;
  row_ = FrameRow{};
  row_.frame = frame;
  row_.time = time;
  row_.dt = dt;
  row_.accuracy_evaluated = accuracy_frame(frame);
  if (camera_cut) pops_.forget_all();
  frame_de_ = {};
  frame_rel_ = {};
  frame_change_ = {};
  frame_stale_ = {};
  frame_de_viewed_ = {};
  std::fill(std::begin(frame_served_), std::end(frame_served_), 0);
  std::fill(std::begin(frame_demand_), std::end(frame_demand_), 0);
  frame_costs_given_ = false;
}

PopEvaluation RunMetrics::receiver(std::uint64_t id, std::span<const Rgb> planner_e,
                                   std::span<const Rgb> reference_e, const LookupResult& lookup,
                                   const ReceiverViewing& view, int stratum) {
  require_frame("receiver");
  const std::size_t n = settings_.normals.size();
  if (planner_e.size() != n || reference_e.size() != n) {
    throw std::invalid_argument("metrics: receiver " + std::to_string(id) + " needs " +
                                std::to_string(n) + " planner and reference irradiances");
  }
  const double weight = view.weight > 0.0 && std::isfinite(view.weight) ? view.weight : 0.0;
  ReceiverTotals& totals = tally_.at(id, stratum);
  totals.seconds += row_.dt;
  totals.viewed_seconds += weight * row_.dt;
  double error_sum = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    planner_lab_[k] = display_lab(planner_e[k], settings_.exposure);
    reference_lab_[k] = display_lab(reference_e[k], settings_.exposure);
    share_[k] = weight > 0.0 ? normal_visible_share(settings_.normals[k], view.to_camera) : 0.0;
    error_sum += display_difference(planner_lab_[k], reference_lab_[k]);
  }
  if (row_.accuracy_evaluated) {
    for (std::size_t k = 0; k < n; ++k) {
      const double de = display_difference(planner_lab_[k], reference_lab_[k]);
      const double rel = relative_error(planner_e[k], reference_e[k], settings_.rel_error_floor);
      frame_de_.add(de);
      frame_rel_.add(rel);
      de_.add(de);
      rel_.add(rel);
      de_samples_.push_back(static_cast<float>(de));
      rel_samples_.push_back(static_cast<float>(rel));
      totals.de_sum += de;
      ++totals.samples;
      const double w = weight * share_[k];
      if (w > 0.0) {
        totals.viewed_de_sum += w * de;
        totals.viewed_weight += w;
        frame_de_viewed_.add(de, w);
        de_viewed_.add(de, w);
        de_viewed_max_.add(de);
        de_viewed_samples_.push_back({static_cast<float>(de), static_cast<float>(w)});
      }
    }
  }
  const PopEvaluation ev = pops_.update(id, row_.frame, planner_lab_, reference_lab_, share_);
  if (ev.has_previous) {
    frame_change_.add(ev.change);
    change_.add(ev.change);
    if (weight > 0.0) change_viewed_.add(ev.viewed_change);
  }
  if (ev.pop) {
    ++totals.pops;
    ++row_.pops;
    ++pop_count_;
    pop_sum_ += ev.change;
  }
  if (ev.viewed_pop && weight > 0.0) {
    ++row_.viewed_pops;
    ++viewed_pop_count_;
    viewed_pop_weight_ += weight;
    totals.viewed_pop_weight += weight;
  }
  row_.view_weight += weight;
  response_.update(id, row_.frame, row_.time, reference_lab_, error_sum / static_cast<double>(n));
  if (!lookup.fell_back) {
    const double stale = row_.time - lookup.data_time;
    frame_stale_.add(stale);
    stale_.add(stale);
  }
  ++row_.receivers;
  return ev;
}

void RunMetrics::demand_point(const LookupResult& lookup, double distance_to_camera_m,
                              DemandKind kind) {
  require_frame("demand_point");
  const int k = kind_index(kind);
  ++frame_demand_[k];
  if (is_served(lookup, distance_to_camera_m, settings_.coverage)) ++frame_served_[k];
}

void RunMetrics::costs(const FrameCosts& c) {
  require_frame("costs");
  if (frame_costs_given_) throw std::logic_error("metrics: costs given twice in a frame");
  frame_costs_given_ = true;
  row_.live_probes = c.live_probes;
  row_.bytes = c.bytes;
  row_.faces_granted = c.faces_granted;
  row_.faces_used = c.faces_used;
  cost_sums_.faces_requested += c.faces_requested;
  cost_sums_.faces_granted += c.faces_granted;
  cost_sums_.faces_used += c.faces_used;
  cost_sums_.faces_refused += c.faces_refused;
  cost_sums_.captures_refused += c.captures_refused;
}

FrameRow RunMetrics::end_frame() {
  require_frame("end_frame");
  in_frame_ = false;
  pops_.end_frame(row_.frame);
  response_.end_frame(row_.frame);
  const double dt = row_.dt;

  row_.de2000_mean = frame_de_.mean();
  row_.de2000_viewed_mean = frame_de_viewed_.mean();
  row_.de2000_max = frame_de_.max();
  row_.rel_mean = frame_rel_.mean();
  row_.change_max = frame_change_.max();
  row_.staleness_mean = frame_stale_.mean();

  const int r = kind_index(DemandKind::receiver);
  std::int64_t served = 0;
  std::int64_t demand = 0;
  for (int k = 0; k < 3; ++k) {
    served += frame_served_[k];
    demand += frame_demand_[k];
  }
  row_.demand_points = demand;
  row_.coverage = demand > 0 ? share(served, demand) : std::nan("");
  if (demand > 0) coverage_all_.add(row_.coverage, dt);
  if (frame_demand_[r] > 0) coverage_receivers_.add(share(frame_served_[r], frame_demand_[r]), dt);
  if (demand > frame_demand_[r]) {
    coverage_ground_.add(share(served - frame_served_[r], demand - frame_demand_[r]), dt);
  }
  demand_samples_ += demand;

  ++frames_;
  duration_s_ += dt;
  receiver_seconds_ += static_cast<double>(row_.receivers) * dt;
  viewed_seconds_ += row_.view_weight * dt;
  receiver_frames_ += row_.receivers;
  max_live_ = std::max(max_live_, row_.live_probes);
  max_bytes_ = std::max(max_bytes_, row_.bytes);
  live_mean_.add(static_cast<double>(row_.live_probes), dt);
  bytes_mean_.add(static_cast<double>(row_.bytes), dt);
  return row_;
}

Summary RunMetrics::summary() const {
  Summary s;
  s.frames = frames_;
  s.duration_s = duration_s_;
  s.receiver_minutes = receiver_seconds_ / 60.0;
  s.viewed_receiver_minutes = viewed_seconds_ / 60.0;
  s.receiver_frames = receiver_frames_;
  s.samples = de_.count();
  s.sample.stride = sample_stride_;
  s.sample.receivers_scored = static_cast<std::int64_t>(tally_.size());
  s.sample.receivers_lit = std::max(receivers_lit_, s.sample.receivers_scored);
  if (sample_stride_ > 1) {
    // 400 replicates: the interval ends move by about 1% of its width between seeds.
    s.sample.ci95 = bootstrap_intervals(tally_.totals(), 400, 0x5a3f1e77u);
  }
  {
    std::vector<WeightedSample> viewed = de_viewed_samples_;  // sorted by the percentile
    s.de2000_viewed = {de_viewed_.mean(), weighted_percentile(viewed, 95.0), de_viewed_max_.max()};
  }
  s.de2000 = {de_.mean(), percentile_nearest_rank(std::span<const float>(de_samples_), 95.0),
              de_.max()};
  s.rel = {rel_.mean(), percentile_nearest_rank(std::span<const float>(rel_samples_), 95.0),
           rel_.max()};
  s.pops.count = pop_count_;
  s.pops.sum = pop_sum_;
  s.pops.max = change_.max();
  s.pops.per_min = s.receiver_minutes > 0.0 ? static_cast<double>(pop_count_) / s.receiver_minutes
                                            : std::nan("");
  s.pops_viewed.count = viewed_pop_count_;
  s.pops_viewed.sum = viewed_pop_weight_;
  s.pops_viewed.max = change_viewed_.max();
  s.pops_viewed.per_min = s.viewed_receiver_minutes > 0.0
                              ? viewed_pop_weight_ / s.viewed_receiver_minutes
                              : std::nan("");
  s.response = response_.summary();
  s.coverage.mean = coverage_all_.mean();
  s.coverage.receivers = coverage_receivers_.mean();
  s.coverage.ground = coverage_ground_.mean();
  s.coverage.samples = demand_samples_;
  s.staleness.mean = stale_.mean();
  s.staleness.max = stale_.max();
  s.faces.requested = cost_sums_.faces_requested;
  s.faces.granted = cost_sums_.faces_granted;
  s.faces.used = cost_sums_.faces_used;
  s.faces.refused = cost_sums_.faces_refused;
  s.captures_refused = cost_sums_.captures_refused;
  s.bake = bake_;
  s.probes.max_live = max_live_;
  s.probes.mean_live = live_mean_.mean();
  s.memory.max_bytes = max_bytes_;
  s.memory.mean_bytes = bytes_mean_.mean();
  return s;
}

nlohmann::ordered_json RunMetrics::to_json(const Summary& s) {
  using J = nlohmann::ordered_json;
  const auto err = [](const ErrorSummary& e) {
    J j;
    j["mean"] = number_or_null(e.mean);
    j["p95"] = number_or_null(e.p95);
    j["max"] = number_or_null(e.max);
    return j;
  };
  J j;
  j["frames"] = s.frames;
  j["duration_s"] = number_or_null(s.duration_s);
  j["receiver_minutes"] = number_or_null(s.receiver_minutes);
  j["viewed_receiver_minutes"] = number_or_null(s.viewed_receiver_minutes);
  j["receiver_frames"] = s.receiver_frames;
  j["samples"] = s.samples;
  j["error"]["viewed"]["de2000"] = err(s.de2000_viewed);
  j["error"]["uniform"]["de2000"] = err(s.de2000);
  j["error"]["uniform"]["rel"] = err(s.rel);
  j["pops"]["viewed"]["per_min"] = number_or_null(s.pops_viewed.per_min);
  j["pops"]["viewed"]["max"] = number_or_null(s.pops_viewed.max);
  j["pops"]["viewed"]["sum"] = number_or_null(s.pops_viewed.sum);
  j["pops"]["viewed"]["count"] = s.pops_viewed.count;
  j["pops"]["uniform"]["per_min"] = number_or_null(s.pops.per_min);
  j["pops"]["uniform"]["max"] = number_or_null(s.pops.max);
  j["pops"]["uniform"]["sum"] = number_or_null(s.pops.sum);
  j["pops"]["uniform"]["count"] = s.pops.count;
  j["response"]["events"] = s.response.events;
  j["response"]["censored"] = s.response.censored;
  j["response"]["median_s"] = number_or_null(s.response.median_s);
  j["response"]["p95_s"] = number_or_null(s.response.p95_s);
  j["coverage"]["mean"] = number_or_null(s.coverage.mean);
  j["coverage"]["receivers"] = number_or_null(s.coverage.receivers);
  j["coverage"]["ground"] = number_or_null(s.coverage.ground);
  j["coverage"]["samples"] = s.coverage.samples;
  j["staleness"]["mean"] = number_or_null(s.staleness.mean);
  j["staleness"]["max"] = number_or_null(s.staleness.max);
  j["faces"]["requested"] = s.faces.requested;
  j["faces"]["granted"] = s.faces.granted;
  j["faces"]["used"] = s.faces.used;
  j["faces"]["refused"] = s.faces.refused;
  j["captures"]["refused"] = s.captures_refused;
  j["bake"]["captures"] = s.bake.captures;
  j["bake"]["faces"] = s.bake.faces;
  j["probes"]["max_live"] = s.probes.max_live;
  j["probes"]["mean_live"] = number_or_null(s.probes.mean_live);
  j["memory"]["max_bytes"] = s.memory.max_bytes;
  j["memory"]["mean_bytes"] = number_or_null(s.memory.mean_bytes);
  j["sample"]["stride"] = s.sample.stride;
  j["sample"]["receivers_scored"] = s.sample.receivers_scored;
  j["sample"]["receivers_lit"] = s.sample.receivers_lit;
  const auto interval = [](const Interval& i) {
    J k;
    k["low"] = number_or_null(i.low);
    k["high"] = number_or_null(i.high);
    return k;
  };
  j["sample"]["ci95"]["de2000_viewed_mean"] = interval(s.sample.ci95.de2000_viewed_mean);
  j["sample"]["ci95"]["de2000_mean"] = interval(s.sample.ci95.de2000_mean);
  j["sample"]["ci95"]["pops_viewed_per_min"] = interval(s.sample.ci95.pops_viewed_per_min);
  j["sample"]["ci95"]["pops_per_min"] = interval(s.sample.ci95.pops_per_min);
  return j;
}

std::string format_number(double x) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  if (x == 0.0) return "0";  // also -0
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, x, std::chars_format::general, 6);
  return std::string(buf, res.ptr);
}

std::string format_number(std::int64_t x) {
  char buf[32];
  const auto res = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, res.ptr);
}

std::string frame_csv_header() {
  return "frame,time,dt,receivers,accuracy,de2000_mean,de2000_max,rel_mean,de2000_viewed_mean,"
         "pops,viewed_pops,change_max,view_weight,demand_points,coverage,staleness_mean,"
         "live_probes,bytes,faces_granted,faces_used";
}

std::string frame_csv_row(const FrameRow& r) {
  return join({format_number(r.frame),
               format_number(r.time),
               format_number(r.dt),
               format_number(r.receivers),
               r.accuracy_evaluated ? "1" : "0",
               format_number(r.de2000_mean),
               format_number(r.de2000_max),
               format_number(r.rel_mean),
               format_number(r.de2000_viewed_mean),
               format_number(r.pops),
               format_number(r.viewed_pops),
               format_number(r.change_max),
               format_number(r.view_weight),
               format_number(r.demand_points),
               format_number(r.coverage),
               format_number(r.staleness_mean),
               format_number(r.live_probes),
               format_number(r.bytes),
               format_number(r.faces_granted),
               format_number(r.faces_used)});
}

std::string summary_csv_header() {
  std::vector<std::pair<std::string, std::string>> cells;
  flatten(RunMetrics::to_json(Summary{}), "", cells);
  std::vector<std::string> names;
  for (auto& c : cells) names.push_back(c.first);
  return join(names);
}

std::string summary_csv_row(const Summary& s) {
  std::vector<std::pair<std::string, std::string>> cells;
  flatten(RunMetrics::to_json(s), "", cells);
  std::vector<std::string> values;
  for (auto& c : cells) values.push_back(c.second);
  return join(values);
}

}  // namespace ambisim
