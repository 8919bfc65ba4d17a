#include "policies/baselines/scrolling_grid.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "policies/core/container_bytes.h"
#include "policies/core/default_ambient.h"

namespace ambisim {
namespace {

// Fades end after this many time constants (99.3 % of the way; the last 0.7 % snaps).
constexpr double kFadeEnd = 5.0;

float luminance_l0(const Sh9Rgb& sh) {
  const Rgb& c = sh.c[0];
  return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z;
}

}  // namespace

PlannerInfo ScrollingGridPlanner::info() {
  std::vector<ParamSpec> params = {
      integer_param("nx", 9, Range::closed(1, 256), "probes along x (east)"),
      integer_param("ny", 9, Range::closed(1, 256), "probes along y (north)"),
      integer_param("nz", 3, Range::closed(1, 64), "probe layers"),
      number_param("spacing_m", 8.0, Range::positive(), "horizontal probe spacing"),
      number_param("vertical_spacing_m", 2.0, Range::positive(), "vertical probe spacing"),
      number_param("height_m", 1.5, Range{},
                   "middle layer: the lattice level nearest this height above the ground under "
                   "the grid centre"),
      number_param("blend_s", 0.5, Range::non_negative(),
                   "hysteresis time constant: a probe moves to a new capture as 1 - exp(-t / "
                   "blend_s)"),
      number_param("big_change", 0.5, Range::non_negative(),
                   "relative L0 luminance change above which the faster blend applies (0: off)"),
      number_param("big_change_blend_s", 0.1, Range::non_negative(),
                   "time constant used for a big change (never slower than blend_s)"),
      bool_param("predict", false, "centre the grid at the predicted focus (velocity prediction)"),
      number_param("lookahead_s", 0.5, Range::non_negative(),
                   "with predict: look-ahead beyond the capture latency")};
  for (auto& s : coefficient_format_params()) params.push_back(std::move(s));
  return {"grid", "camera-centred scrolling probe grid with hysteresis blending (DDGI/RTXGI style)",
          std::move(params),
          [](const PlannerParams& p) { return std::make_unique<ScrollingGridPlanner>(p); }};
}

ScrollingGridPlanner::ScrollingGridPlanner(const PlannerParams& params)
    : params_(params),
      format_(coefficient_format_from(params)),
      nx_(params.integer("nx")),
      ny_(params.integer("ny")),
      nz_(params.integer("nz")),
      spacing_m_(params.number("spacing_m")),
      vertical_spacing_m_(params.number("vertical_spacing_m")),
      height_m_(params.number("height_m")),
      blend_s_(params.number("blend_s")),
      big_change_(params.number("big_change")),
      big_change_blend_s_(params.number("big_change_blend_s")) {
  prediction_.enabled = params.boolean("predict");
  prediction_.lookahead_s = params.number("lookahead_s");
}

glm::dvec3 ScrollingGridPlanner::position_of(const Key& k) const {
  return {static_cast<double>(k[0]) * spacing_m_, static_cast<double>(k[1]) * spacing_m_,
          static_cast<double>(k[2]) * vertical_spacing_m_};
}

bool ScrollingGridPlanner::has_data(const Key& k) const {
  auto it = probes_.find(k);
  return it != probes_.end() && it->second.has_data;
}

void ScrollingGridPlanner::place_window(const glm::dvec3& focus, const FrameContext& ctx) {
  const WorldQueries* world = ctx.world;
  // The solid top: terrain or canopy (a probe inside a crown sees its backfaces as one inside
  // a hill does, L318).
  const bool have_surface = world != nullptr && static_cast<bool>(world->surface_height);
  const bool have_ground = world != nullptr && static_cast<bool>(world->ground_height);
  auto ground = [&](double x, double y) {
    if (have_surface) return world->surface_height(x, y);
    return have_ground ? world->ground_height(x, y) : 0.0;
  };

  Key c{std::llround(focus.x / spacing_m_), std::llround(focus.y / spacing_m_), centre_[2]};
  const double target_k =
      (ground(static_cast<double>(c[0]) * spacing_m_, static_cast<double>(c[1]) * spacing_m_) +
       height_m_) /
      vertical_spacing_m_;
  if (!placed_ || ctx.camera_cut || std::abs(target_k - static_cast<double>(c[2])) > 0.75) {
    c[2] = std::llround(target_k);
  }
  if (placed_ && c == centre_) return;
  placed_ = true;
  centre_ = c;
  const Key n{nx_, ny_, nz_};
  for (int a = 0; a < 3; ++a) {
    lo_[a] = c[a] - (n[a] - 1) / 2;
    hi_[a] = lo_[a] + n[a] - 1;
  }
  // Keep the probes still inside (their data survives the scroll), add the new slab.
  std::map<Key, Probe> next;
  for (Key k{lo_[0], 0, 0}; k[0] <= hi_[0]; ++k[0]) {
    for (k[1] = lo_[1]; k[1] <= hi_[1]; ++k[1]) {
      for (k[2] = lo_[2]; k[2] <= hi_[2]; ++k[2]) {
        if (auto it = probes_.find(k); it != probes_.end()) {
          next.emplace(k, it->second);
          continue;
        }
        // DDGI relocation and classification: a probe less than kClearance_m above the solid
        // top moves up by at most half a vertical cell (its light still stands for its lattice
        // point, as DDGI's relocated probes do); one deeper inside is inactive.
        const glm::dvec3 p = position_of(k);
        const double lift = ground(p.x, p.y) + kClearance_m - p.z;
        if (lift <= 0.5 * vertical_spacing_m_) {
          Probe q;
          q.lift_m = std::max(lift, 0.0);
          next.emplace(k, q);
        } else {
          ++dropped_in_solids_;
        }
      }
    }
  }
  probes_ = std::move(next);
}

std::vector<CaptureRequest> ScrollingGridPlanner::plan(const FrameContext& ctx) {
  pending_.clear();  // anything neither started nor refused last frame never started
  now_ = ctx.time;
  focus_ = make_focus(ctx, prediction_);
  place_window(focus_.ahead, ctx);
  if (ctx.startable_captures <= 0) return {};

  // Priority: (never captured first, then by score), score = distance for never-captured
  // (smaller first), -age / (1 + distance / spacing) otherwise; ties by lattice index.
  struct Candidate {
    bool captured;
    double score;
    Key key;
    bool operator<(const Candidate& o) const {
      if (captured != o.captured) return !captured;
      if (score != o.score) return score < o.score;
      return key < o.key;
    }
  };
  std::vector<Candidate> cands;
  cands.reserve(probes_.size());
  for (const auto& [k, q] : probes_) {
    if (q.in_flight) continue;
    const double d = focus_.distance(position_of(k));
    if (!q.has_data) {
      cands.push_back({false, d, k});
    } else {
      cands.push_back({true, -(now_ - q.last_request) / (1.0 + d / spacing_m_), k});
    }
  }
  const std::size_t n = std::min(cands.size(), static_cast<std::size_t>(ctx.startable_captures));
  std::partial_sort(cands.begin(), cands.begin() + static_cast<std::ptrdiff_t>(n), cands.end());
  std::vector<CaptureRequest> out;
  out.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint64_t tag = next_tag_++;
    pending_[tag] = cands[i].key;
    const Key& k = cands[i].key;
    out.push_back({position_of(k) + glm::dvec3(0.0, 0.0, probes_.at(k).lift_m), tag});
  }
  return out;
}

void ScrollingGridPlanner::started(std::uint64_t tag) {
  auto it = pending_.find(tag);
  if (it == pending_.end()) return;
  if (auto p = probes_.find(it->second); p != probes_.end()) {
    p->second.in_flight = true;
    p->second.last_request = now_;
  }
  in_flight_[tag] = it->second;
  pending_.erase(it);
}

void ScrollingGridPlanner::refused(std::uint64_t tag) { pending_.erase(tag); }

double ScrollingGridPlanner::target_weight(const Probe& q) const {
  if (!q.fading) return 1.0;
  if (!q.fade_start_known) return 0.0;  // delivered, not yet usable
  return 1.0 - std::exp(-(now_ - q.fade_start) / q.tau);
}

Sh9Rgb ScrollingGridPlanner::value_of(const Probe& q) const {
  if (!q.fading) return q.target;
  return sh_lerp(q.start, q.target, static_cast<float>(target_weight(q)));
}

double ScrollingGridPlanner::data_time_of(const Probe& q) const {
  if (!q.fading) return q.target_time;
  return q.start_time + target_weight(q) * (q.target_time - q.start_time);
}

void ScrollingGridPlanner::deliver(const FinishedProbe& probe) {
  auto f = in_flight_.find(probe.tag);
  if (f == in_flight_.end()) return;
  const Key key = f->second;
  in_flight_.erase(f);
  auto it = probes_.find(key);
  if (it == probes_.end()) return;  // scrolled out of the window while it was rendered
  Probe& q = it->second;
  // A newer capture of the same point may still be in flight; this one is still fresh data.
  q.in_flight = std::any_of(in_flight_.begin(), in_flight_.end(),
                            [&](const auto& kv) { return kv.second == key; });
  const Sh9Rgb fresh = format_.store(probe.sh);
  // Fade from what this probe showed, or for a first capture from what lookups here returned
  // (its neighbours or the coarse fallback), so a probe's arrival does not pop either.
  Sh9Rgb from;
  double from_time = 0.0;
  bool have_from = true;
  if (q.has_data) {
    from = value_of(q);
    from_time = data_time_of(q);
  } else {
    const LookupResult before = lookup(position_of(key));
    have_from = before.contributor_count > 0;
    from = before.sh;
    from_time = before.data_time;
  }
  q.has_data = true;
  q.fading = false;
  if (have_from) {
    const float was = luminance_l0(from);
    const float now = luminance_l0(fresh);
    const bool big =
        big_change_ > 0.0 && std::abs(now - was) > big_change_ * std::max(std::abs(was), 1e-6f);
    q.tau = big ? std::min(big_change_blend_s_, blend_s_) : blend_s_;
    q.start = format_.store(from);
    q.start_time = from_time;
    q.fading = q.tau > 0.0;
    q.fade_start_known = false;
  }
  q.target = fresh;
  q.target_time = probe.requested_time;
  q.tag = probe.tag;
}

void ScrollingGridPlanner::update(const FrameContext& ctx) {
  now_ = ctx.time;
  for (auto& [k, q] : probes_) {
    if (q.fading && !q.fade_start_known) {
      q.fade_start = now_;
      q.fade_start_known = true;
    } else if (q.fading && now_ - q.fade_start >= kFadeEnd * q.tau) {
      q.fading = false;
    }
  }
}

LookupResult ScrollingGridPlanner::nearest_fallback(const glm::dvec3& p) const {
  LookupResult r;
  r.fell_back = true;
  r.spacing_m = std::numeric_limits<double>::infinity();
  const Probe* best = nullptr;
  double best_d = std::numeric_limits<double>::infinity();
  for (const auto& [k, q] : probes_) {  // ties: the lower lattice index
    if (!q.has_data) continue;
    const double d = glm::distance(position_of(k), p);
    if (d < best_d) {
      best_d = d;
      best = &q;
    }
  }
  if (best == nullptr) return default_ambient_lookup();
  r.sh = value_of(*best);
  r.contributors[0] = {best->tag, 1.0f};
  r.contributor_count = 1;
  r.spacing_m = best_d;
  r.data_time = data_time_of(*best);
  return r;
}

LookupResult ScrollingGridPlanner::lookup(const glm::dvec3& p) const {
  LookupResult r;
  r.fell_back = true;
  r.spacing_m = std::numeric_limits<double>::infinity();
  if (probes_.empty()) return default_ambient_lookup();

  // Lattice coordinates, clamped to the window's box.
  const std::array<double, 3> cell{spacing_m_, spacing_m_, vertical_spacing_m_};
  std::array<double, 3> u{};
  std::array<std::int64_t, 3> i0{};
  std::array<double, 3> f{};
  glm::dvec3 clamped{0.0};
  for (int a = 0; a < 3; ++a) {
    u[a] = std::clamp(p[a] / cell[a], static_cast<double>(lo_[a]), static_cast<double>(hi_[a]));
    clamped[a] = u[a] * cell[a];
    const double fl = std::floor(u[a]);
    i0[a] = std::min(static_cast<std::int64_t>(fl), std::max(lo_[a], hi_[a] - 1));
    f[a] = std::clamp(u[a] - static_cast<double>(i0[a]), 0.0, 1.0);
  }
  const double outside = glm::length(p - clamped);
  if (!std::isfinite(outside)) return default_ambient_lookup();

  struct Corner {
    const Probe* probe;
    double w;
  };
  std::array<Corner, 8> corners{};
  int n = 0;
  double total = 0.0;
  for (int c = 0; c < 8; ++c) {
    const Key k{i0[0] + (c & 1), i0[1] + ((c >> 1) & 1), i0[2] + ((c >> 2) & 1)};
    auto it = probes_.find(k);
    if (it == probes_.end() || !it->second.has_data) continue;
    double w = 1.0;
    for (int a = 0; a < 3; ++a) w *= ((c >> a) & 1) ? f[a] : 1.0 - f[a];
    corners[static_cast<std::size_t>(n++)] = {&it->second, w};
    total += w;
  }
  if (n == 0) return nearest_fallback(p);
  if (total > 0.0) {
    // Only corners that carry weight contribute.
    n = static_cast<int>(std::remove_if(corners.begin(), corners.begin() + n,
                                        [](const Corner& c) { return c.w <= 0.0; }) -
                         corners.begin());
  } else {
    // Every corner with data has zero trilinear weight (p sits on the face of probes without
    // data): share equally among them rather than report nothing.
    for (int c = 0; c < n; ++c) corners[static_cast<std::size_t>(c)].w = 1.0;
    total = n;
  }
  r.sh = Sh9Rgb{};
  r.data_time = 0.0;
  for (int c = 0; c < n; ++c) {
    const Corner& k = corners[static_cast<std::size_t>(c)];
    const double w = k.w / total;
    r.sh += value_of(*k.probe) * static_cast<float>(w);
    r.data_time += w * data_time_of(*k.probe);
    r.contributors[static_cast<std::size_t>(c)] = {k.probe->tag, static_cast<float>(w)};
  }
  r.contributor_count = n;
  r.fell_back = outside > 1e-9;
  r.spacing_m = spacing_m_ + (r.fell_back ? outside : 0.0);
  return r;
}

PlannerStats ScrollingGridPlanner::stats() const {
  PlannerStats s;
  std::int64_t sets = 0;
  for (const auto& [k, q] : probes_) {
    if (q.has_data) ++sets;
    if (q.fading) ++sets;  // the start set of a fade
  }
  s.live_probes = sets;
  s.nodes = static_cast<std::int64_t>(probes_.size());
  // Sets count in their storage format; the in-memory Sh9Rgb copies inside Probe are not
  // counted twice. Structure: map nodes (key, the rest of Probe, links) for probes and captures.
  const std::size_t probe_node =
      sizeof(Key) + sizeof(Probe) - 2 * sizeof(Sh9Rgb) + kMapNodeOverhead;
  const std::size_t tag_node = sizeof(std::uint64_t) + sizeof(Key) + kMapNodeOverhead;
  s.bytes = static_cast<std::int64_t>(static_cast<std::size_t>(sets) * format_.bytes_per_set() +
                                      probes_.size() * probe_node +
                                      (pending_.size() + in_flight_.size()) * tag_node);
  return s;
}

void ScrollingGridPlanner::describe_nodes(std::vector<ProbeNodeView>& out) const {
  for (const auto& [k, q] : probes_) {
    ProbeNodeView v;
    v.centre = position_of(k);
    v.has_data = q.has_data;
    v.in_flight = q.in_flight;
    v.age_s = q.has_data ? now_ - data_time_of(q) : 0.0;
    if (q.has_data) v.sh = value_of(q);
    out.push_back(v);
  }
}

}  // namespace ambisim
