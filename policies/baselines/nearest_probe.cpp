#include "policies/baselines/nearest_probe.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "policies/core/container_bytes.h"
#include "policies/core/default_ambient.h"
#include "policies/core/solid_clearance.h"

namespace ambisim {

PlannerInfo NearestProbePlanner::info() {
  return {
      "nearest",
      "nearest finished probe with time averaging (Half-Life 2 style); captures at the camera",
      {number_param("spacing_m", 8.0, Range::positive(),
                    "request a capture when no finished or in-flight probe is this close to "
                    "the camera"),
       integer_param("max_probes", 256, Range::closed(1, 1e9),
                     "probes kept; beyond it the one farthest from the camera is evicted"),
       number_param("lifetime_s", 60.0, Range::positive(),
                    "a probe is dropped this long after it was requested"),
       number_param("blend_s", 0.5, Range::non_negative(),
                    "a new probe fades in over this time from the value it replaces"),
       bool_param("predict", false, "capture where the camera will be one capture latency ahead")},
      [](const PlannerParams& p) { return std::make_unique<NearestProbePlanner>(p); }};
}

NearestProbePlanner::NearestProbePlanner(const PlannerParams& params)
    : params_(params),
      spacing_m_(params.number("spacing_m")),
      max_probes_(static_cast<std::size_t>(params.integer("max_probes"))),
      lifetime_s_(params.number("lifetime_s")),
      blend_s_(params.number("blend_s")),
      predict_(params.boolean("predict")) {}

std::optional<std::size_t> NearestProbePlanner::nearest(const glm::dvec3& p,
                                                        double* distance) const {
  std::optional<std::size_t> best;
  double best_d = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < probes_.size(); ++i) {
    const double d = glm::distance(probes_[i].position, p);
    if (d < best_d) {
      best_d = d;
      best = i;
    }
  }
  if (distance) *distance = best_d;
  return best;
}

std::vector<CaptureRequest> NearestProbePlanner::plan(const FrameContext& ctx) {
  pending_.clear();  // anything neither started nor refused last frame never started
  camera_ = ctx.camera_position;
  if (ctx.startable_captures <= 0) return {};
  glm::dvec3 target = ctx.camera_position;
  const double latency = ctx.capture_latency_s();  // infinite when no faces are granted
  if (predict_ && !ctx.camera_cut && std::isfinite(latency)) {
    target += ctx.camera_velocity * latency;
  }
  target = above_solids(ctx.world, target, kSolidClearance_m);

  double d = std::numeric_limits<double>::infinity();
  nearest(target, &d);
  for (const auto& [tag, f] : in_flight_) d = std::min(d, glm::distance(f.position, target));
  if (d <= spacing_m_) return {};

  const std::uint64_t tag = next_tag_++;
  pending_[tag] = {target, ctx.time};
  return {{target, tag}};
}

void NearestProbePlanner::started(std::uint64_t tag) {
  auto it = pending_.find(tag);
  if (it == pending_.end()) return;
  in_flight_[tag] = it->second;
  pending_.erase(it);
}

void NearestProbePlanner::refused(std::uint64_t tag) { pending_.erase(tag); }

float NearestProbePlanner::fade_weight(const Probe& q) const {
  if (!q.fading) return 1.0f;
  if (!q.fade_start_known) return 0.0f;  // delivered, not yet usable
  const double t = (now_ - q.fade_start) / blend_s_;
  return static_cast<float>(std::clamp(t, 0.0, 1.0));
}

void NearestProbePlanner::deliver(const FinishedProbe& probe) {
  in_flight_.erase(probe.tag);
  Probe q;
  q.tag = probe.tag;
  q.position = probe.position;
  q.sh = probe.sh;
  q.data_time = probe.requested_time;
  // What lookups here returned just before: the value to fade from (none for the first probe:
  // it replaces the default ambient, which is no data to average with).
  const LookupResult before = lookup(probe.position);
  if (!before.fell_back && blend_s_ > 0.0) {
    q.fading = true;
    q.from = before.sh;
    q.from_tag = before.contributors[0].tag;
    q.from_data_time = before.data_time;
  }
  probes_.push_back(q);
  enforce_cap();
}

void NearestProbePlanner::update(const FrameContext& ctx) {
  now_ = ctx.time;
  camera_ = ctx.camera_position;
  for (auto& q : probes_) {
    if (q.fading && !q.fade_start_known) {
      q.fade_start = now_;
      q.fade_start_known = true;
    } else if (q.fading && now_ - q.fade_start >= blend_s_) {
      q.fading = false;
    }
  }
  std::erase_if(probes_, [&](const Probe& q) { return now_ - q.data_time > lifetime_s_; });
  std::erase_if(in_flight_,
                [&](const auto& kv) { return now_ - kv.second.requested_time > lifetime_s_; });
  enforce_cap();
}

void NearestProbePlanner::enforce_cap() {
  while (probes_.size() > max_probes_) {
    std::size_t worst = 0;
    double worst_d = -1.0;
    for (std::size_t i = 0; i < probes_.size(); ++i) {  // ties: the earlier delivered goes
      const double d = glm::distance(probes_[i].position, camera_);
      if (d > worst_d) {
        worst_d = d;
        worst = i;
      }
    }
    probes_.erase(probes_.begin() + static_cast<std::ptrdiff_t>(worst));
  }
}

LookupResult NearestProbePlanner::lookup(const glm::dvec3& p) const {
  LookupResult r;
  double d = 0.0;
  const auto i = nearest(p, &d);
  if (!i) return default_ambient_lookup();
  const Probe& q = probes_[*i];
  const float w = fade_weight(q);
  r.spacing_m = d;
  if (w >= 1.0f) {
    r.sh = q.sh;
    r.contributors[0] = {q.tag, 1.0f};
    r.contributor_count = 1;
    r.data_time = q.data_time;
    return r;
  }
  r.sh = sh_lerp(q.from, q.sh, w);
  r.contributors[0] = {q.tag, w};
  r.contributors[1] = {q.from_tag, 1.0f - w};
  r.contributor_count = 2;
  r.data_time = q.from_data_time + w * (q.data_time - q.from_data_time);
  return r;
}

PlannerStats NearestProbePlanner::stats() const {
  PlannerStats s;
  s.live_probes = static_cast<std::int64_t>(probes_.size());
  const std::size_t map_entry =
      sizeof(std::map<std::uint64_t, InFlight>::value_type) + kMapNodeOverhead;
  s.bytes = static_cast<std::int64_t>(probes_.size() * sizeof(Probe) +
                                      (pending_.size() + in_flight_.size()) * map_entry);
  return s;
}

void NearestProbePlanner::describe_nodes(std::vector<ProbeNodeView>& out) const {
  for (const auto& q : probes_) {
    ProbeNodeView v;
    v.centre = q.position;
    v.has_data = true;
    v.age_s = now_ - q.data_time;
    v.sh = q.sh;
    out.push_back(v);
  }
  for (const auto& [tag, f] : in_flight_) {
    ProbeNodeView v;
    v.centre = f.position;
    v.in_flight = true;
    out.push_back(v);
  }
}

}  // namespace ambisim
