#include "policies/baselines/relit.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "policies/core/container_bytes.h"
#include "policies/core/default_ambient.h"
#include "policies/core/solid_clearance.h"

namespace ambisim {
namespace {

Rgb max0(const Rgb& c) {
  return Rgb(std::max(c.x, 0.0f), std::max(c.y, 0.0f), std::max(c.z, 0.0f));
}

}  // namespace

Rgb relit_ground_irradiance(const LightingInfo& light) {
  Rgb g = max0(sh_irradiance(light.sky_sh, {0.0, 0.0, 1.0}));
  if (light.sun_on) g += light.sun_irradiance * static_cast<float>(std::max(light.sun_dir.z, 0.0));
  return g;
}

float relit_sky_visibility(const Sh9Rgb& captured, const Sh9Rgb& sky) {
  const double open = luminance(max0(sh_irradiance(sky, {0.0, 0.0, 1.0})));
  if (!(open > 0.0)) return 0.0f;  // a black sky: all the capture is bounce
  const double seen = luminance(max0(sh_irradiance(captured, {0.0, 0.0, 1.0})));
  return static_cast<float>(std::clamp(seen / open, 0.0, 1.0));
}

RelitTransfer relit_transfer(const Sh9Rgb& captured, const LightingInfo& at_capture,
                             const CoefficientFormat& format) {
  RelitTransfer t;
  t.captured = format.store(captured);
  t.sky0 = format.store(at_capture.sky_sh);
  t.ground0 = relit_ground_irradiance(at_capture);
  t.sky_visibility = relit_sky_visibility(t.captured, t.sky0);
  t.relightable = true;
  return t;
}

Sh9Rgb relight(const RelitTransfer& t, const LightingInfo& now, const CoefficientFormat& format) {
  const Sh9Rgb sky = format.store(now.sky_sh);
  const Rgb ground = relit_ground_irradiance(now);
  glm::dvec3 g_minus_1(0.0);  // per channel; no light to scale at t0: keep the capture's
  for (int ch = 0; ch < 3; ++ch) {
    if (t.ground0[ch] > 0.0f) {
      g_minus_1[ch] = static_cast<double>(ground[ch]) / static_cast<double>(t.ground0[ch]) - 1.0;
    }
  }
  const double v = t.sky_visibility;
  Sh9Rgb out;
  for (int k = 0; k < kShCount; ++k) {
    const glm::dvec3 l(t.captured.c[k]), s0(t.sky0.c[k]), s(sky.c[k]);
    // A correction of the capture: exactly zero when nothing changed.
    const glm::dvec3 change = v * (s - s0) + g_minus_1 * (l - v * s0);
    out.c[k] = t.captured.c[k] + Rgb(change);
  }
  return out;
}

PlannerInfo RelitPlanner::info() {
  std::vector<ParamSpec> specs = {
      number_param("spacing_m", 8.0, Range::positive(),
                   "request a capture when no finished or in-flight probe is this close to "
                   "the camera"),
      integer_param("max_probes", 256, Range::closed(1, 1e9),
                    "probes kept; beyond it the one farthest from the camera is evicted"),
      number_param("blend_s", 0.5, Range::non_negative(),
                   "a new probe fades in over this time from the value it replaces")};
  for (auto& s : coefficient_format_params()) specs.push_back(std::move(s));
  return {"relit",
          "probes captured once at the camera, relit every frame from the current sun and sky "
          "(Far Cry 3 radiance transfer, APV sky occlusion)",
          std::move(specs),
          [](const PlannerParams& p) { return std::make_unique<RelitPlanner>(p); }};
}

RelitPlanner::RelitPlanner(const PlannerParams& params)
    : params_(params),
      spacing_m_(params.number("spacing_m")),
      max_probes_(static_cast<std::size_t>(params.integer("max_probes"))),
      blend_s_(params.number("blend_s")),
      format_(coefficient_format_from(params)) {}

bool RelitPlanner::relighting(const WorldQueries* world) const {
  return world != nullptr && !world->lighting_static && static_cast<bool>(world->lighting);
}

std::optional<std::size_t> RelitPlanner::nearest(const glm::dvec3& p, double* distance) const {
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

const RelitPlanner::Probe* RelitPlanner::find(std::uint64_t tag) const {
  for (const auto& q : probes_) {
    if (q.tag == tag) return &q;
  }
  return nullptr;
}

std::vector<CaptureRequest> RelitPlanner::plan(const FrameContext& ctx) {
  pending_.clear();  // anything neither started nor refused last frame never started
  camera_ = ctx.camera_position;
  if (ctx.startable_captures <= 0) return {};
  const glm::dvec3 target = above_solids(ctx.world, ctx.camera_position, kSolidClearance_m);
  double d = std::numeric_limits<double>::infinity();
  nearest(target, &d);
  for (const auto& [tag, f] : in_flight_) d = std::min(d, glm::distance(f.position, target));
  if (d <= spacing_m_) return {};

  const std::uint64_t tag = next_tag_++;
  pending_[tag] = {target, ctx.time};
  return {{target, tag}};
}

void RelitPlanner::started(std::uint64_t tag) {
  auto it = pending_.find(tag);
  if (it == pending_.end()) return;
  in_flight_[tag] = it->second;
  pending_.erase(it);
}

void RelitPlanner::refused(std::uint64_t tag) { pending_.erase(tag); }

float RelitPlanner::fade_weight(const Probe& q) const {
  if (!q.fading) return 1.0f;
  if (!q.fade_start_known) return 0.0f;  // delivered, not yet usable
  const double t = (now_ - q.fade_start) / blend_s_;
  return static_cast<float>(std::clamp(t, 0.0, 1.0));
}

void RelitPlanner::deliver(const FinishedProbe& probe) {
  in_flight_.erase(probe.tag);
  Probe q;
  q.tag = probe.tag;
  q.position = probe.position;
  q.data_time = probe.requested_time;
  if (relighting(world_)) {
    // The faces were rendered one per granted face between request and delivery: the light
    // of the middle of that span stands for them all.
    const double t0 = 0.5 * (probe.requested_time + probe.finished_time);
    q.transfer = relit_transfer(probe.sh, world_->lighting(t0), format_);
    q.relit = light_ ? format_.store(relight(q.transfer, *light_, format_)) : q.transfer.captured;
  } else {
    // Light that never changes: nothing to relight, the capture is the answer.
    q.transfer.captured = format_.store(probe.sh);
    q.relit = q.transfer.captured;
  }
  // What lookups here returned just before: the value to fade from (none for the first probe:
  // it replaces the default ambient, which is no data to average with).
  const LookupResult before = lookup(probe.position);
  if (!before.fell_back && blend_s_ > 0.0) {
    q.fading = true;
    q.from = before.sh;
    q.from_now = before.sh;
    q.from_tag = before.contributors[0].tag;
    q.from_data_time = before.data_time;
    if (const Probe* src = find(q.from_tag)) q.from_base = src->relit;
  }
  probes_.push_back(q);
  enforce_cap();
}

void RelitPlanner::update(const FrameContext& ctx) {
  now_ = ctx.time;
  camera_ = ctx.camera_position;
  world_ = ctx.world;
  if (relighting(world_)) {
    light_ = world_->lighting(now_);
    for (auto& q : probes_) {
      if (q.transfer.relightable) q.relit = format_.store(relight(q.transfer, *light_, format_));
    }
  }
  for (auto& q : probes_) {
    if (q.fading && !q.fade_start_known) {
      q.fade_start = now_;
      q.fade_start_known = true;
    } else if (q.fading && now_ - q.fade_start >= blend_s_) {
      q.fading = false;
    }
  }
  // A fade's source follows the relighting of the probe it came from (while that one lives):
  // its value at delivery plus that probe's change since, exactly `from` when nothing changed.
  for (auto& q : probes_) {
    if (!q.fading) continue;
    const Probe* src = find(q.from_tag);
    if (src == nullptr) continue;  // evicted: the source stays as it was last relit
    Sh9Rgb now = q.from;
    for (int k = 0; k < kShCount; ++k) now.c[k] += src->relit.c[k] - q.from_base.c[k];
    q.from_now = now;
  }
  enforce_cap();
}

void RelitPlanner::enforce_cap() {
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

LookupResult RelitPlanner::lookup(const glm::dvec3& p) const {
  LookupResult r;
  double d = 0.0;
  const auto i = nearest(p, &d);
  if (!i) return default_ambient_lookup();
  const Probe& q = probes_[*i];
  const float w = fade_weight(q);
  r.spacing_m = d;
  if (w >= 1.0f) {
    r.sh = q.relit;
    r.contributors[0] = {q.tag, 1.0f};
    r.contributor_count = 1;
    r.data_time = q.data_time;
    return r;
  }
  r.sh = sh_lerp(q.from_now, q.relit, w);
  r.contributors[0] = {q.tag, w};
  r.contributors[1] = {q.from_tag, 1.0f - w};
  r.contributor_count = 2;
  r.data_time = q.from_data_time + w * (q.data_time - q.from_data_time);
  return r;
}

PlannerStats RelitPlanner::stats() const {
  PlannerStats s;
  s.live_probes = static_cast<std::int64_t>(probes_.size());
  // Per probe, in the storage format: the capture, the sky it was captured under and the
  // relit set lookups read; a fading probe also its source, that source's value at delivery
  // and its relit source. The rest of Probe (position, G0, v, times, tags) as laid out.
  // Under light that never changes only the capture is kept (it is the relit set).
  std::size_t sets = 0;
  for (const auto& q : probes_) sets += (q.transfer.relightable ? 3 : 1) + (q.fading ? 3 : 0);
  const std::size_t per_probe = sizeof(Probe) - 6 * sizeof(Sh9Rgb);
  const std::size_t map_entry =
      sizeof(std::map<std::uint64_t, InFlight>::value_type) + kMapNodeOverhead;
  s.bytes = static_cast<std::int64_t>(sets * format_.bytes_per_set() + probes_.size() * per_probe +
                                      (pending_.size() + in_flight_.size()) * map_entry);
  return s;
}

void RelitPlanner::describe_nodes(std::vector<ProbeNodeView>& out) const {
  for (const auto& q : probes_) {
    ProbeNodeView v;
    v.centre = q.position;
    v.has_data = true;
    v.age_s = now_ - q.data_time;
    v.sh = q.relit;
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
