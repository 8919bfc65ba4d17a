#include "policies/baselines/cascades.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "policies/core/container_bytes.h"
#include "policies/core/default_ambient.h"

namespace ambisim {
namespace {

// A blend ends (snaps to its target) once less than exp(-5) (0.7 %) of the way is left, as
// grid's fades do after five time constants.
const double kBlendEnd = std::exp(-5.0);

// Where free air starts above (x, y): the highest surface within kStencil_m, sampled on a
// (2 kSteps + 1)^2 stencil, plus kReliefMargin x the relief on it. The renderer's columns are
// flat-topped world cells (2 m in the shipped worlds) while surface_height interpolates, so
// at a canopy's sharp edge the surface at the point alone can lie below the column it is in.
// The same rule as the baked lattice's free test (policies/baselines/baked_lattice.h).
constexpr double kStencil_m = 1.0;
constexpr int kSteps = 2;
constexpr double kReliefMargin = 0.25;

template <class Surface>
double free_height(const Surface& surface, double x, double y) {
  double hi = -std::numeric_limits<double>::infinity(), lo = -hi;
  constexpr double step = kStencil_m / kSteps;
  for (int a = -kSteps; a <= kSteps; ++a) {
    for (int b = -kSteps; b <= kSteps; ++b) {
      const double h = surface(x + a * step, y + b * step);
      hi = std::max(hi, h);
      lo = std::min(lo, h);
    }
  }
  return hi + kReliefMargin * (hi - lo);
}

}  // namespace

PlannerInfo CascadesPlanner::info() {
  // Defaults: 4 levels of 7 x 7 x 3 at 4 m / 2 m: windows of 24, 48, 96 and 192 m. Odd counts
  // keep each window symmetric about its centre point (the lattice point nearest the camera),
  // as grid's 9 x 9 x 3; 3 layers as grid's (one under the ground, mostly inactive, one at
  // head height, one above). The finest level reaches 3 cells (12 m) around the camera, where
  // the nearest objects are and the eye sees most detail; the coarsest covers 96 m each side,
  // beyond grid's 32 m. 588 lattice points, about 400 active over flat ground (grid: 243).
  std::vector<ParamSpec> params = {
      integer_param("levels", 4, Range::closed(1, 12), "clipmap levels, each twice the spacing"),
      integer_param("nx", 7, Range::closed(1, 256), "probes along x (east) per level"),
      integer_param("ny", 7, Range::closed(1, 256), "probes along y (north) per level"),
      integer_param("nz", 3, Range::closed(1, 64), "probe layers per level"),
      number_param("spacing_m", 4.0, Range::positive(), "horizontal spacing of the finest level"),
      number_param("vertical_spacing_m", 2.0, Range::positive(),
                   "vertical spacing of the finest level"),
      number_param("height_m", 1.5, Range{},
                   "middle layer: the level's lattice height nearest this height above the "
                   "ground under its centre"),
      number_param("clearance_m", 0.25, Range::non_negative(),
                   "probes stay this far above the terrain or canopy (relocated up to 0.45 of "
                   "a vertical cell, else inactive)"),
      number_param("blend_cells", 1.0, Range::non_negative(),
                   "lookups within this many cells of a level's edge blend into the next "
                   "coarser level (0: hard switch)"),
      // RTXGI SDK DDGIVolumeDesc defaults (rtxgi/ddgi/DDGIVolume.h): probeHysteresis 0.97,
      // probeIrradianceThreshold 0.25, probeBrightnessThreshold 0.10; see ddgi_blend.h.
      number_param("hysteresis", 0.97, Range{0.0, 1.0, false, true},
                   "DDGI hysteresis per 60 Hz frame: value = lerp(new, old, h)"),
      number_param("irradiance_threshold", 0.25, Range::non_negative(),
                   "relative L0 change above which the hysteresis drops by 0.75 (0: off)"),
      number_param("brightness_threshold", 0.10, Range::non_negative(),
                   "largest relative brightening of L0 luminance per 60 Hz frame (0: off)"),
      bool_param("fade_in", false,
                 "a first capture blends in from what lookups there returned before (as grid) "
                 "instead of being taken as is (DDGI: no hysteresis on a new probe)"),
      bool_param("predict", false, "centre the levels at the predicted focus"),
      number_param("lookahead_s", 0.5, Range::non_negative(),
                   "with predict: look-ahead beyond the capture latency")};
  for (auto& s : coefficient_format_params()) params.push_back(std::move(s));
  return {"cascades",
          "camera-centred scrolling clipmaps, each level twice the spacing (RTXGI/Lumen/SDFGI "
          "style)",
          std::move(params),
          [](const PlannerParams& p) { return std::make_unique<CascadesPlanner>(p); }};
}

CascadesPlanner::CascadesPlanner(const PlannerParams& params)
    : params_(params),
      format_(coefficient_format_from(params)),
      nx_(params.integer("nx")),
      ny_(params.integer("ny")),
      nz_(params.integer("nz")),
      height_m_(params.number("height_m")),
      clearance_m_(params.number("clearance_m")),
      blend_cells_(params.number("blend_cells")),
      fade_in_(params.boolean("fade_in")) {
  blend_.hysteresis = params.number("hysteresis");
  blend_.irradiance_threshold = params.number("irradiance_threshold");
  blend_.brightness_threshold = params.number("brightness_threshold");
  prediction_.enabled = params.boolean("predict");
  prediction_.lookahead_s = params.number("lookahead_s");
  const auto n = params.integer("levels");
  double s = params.number("spacing_m");
  double vs = params.number("vertical_spacing_m");
  for (std::int64_t l = 0; l < n; ++l) {
    Level lv;
    lv.s = s;
    lv.vs = vs;
    levels_.push_back(lv);
    s *= 2.0;  // exact: the lattices nest bit for bit
    vs *= 2.0;
  }
}

glm::dvec3 CascadesPlanner::lattice_point(int level, const Key& k) const {
  const Level& lv = levels_.at(static_cast<std::size_t>(level));
  return {static_cast<double>(k[0]) * lv.s, static_cast<double>(k[1]) * lv.s,
          static_cast<double>(k[2]) * lv.vs};
}

bool CascadesPlanner::is_active(int level, const Key& k) const {
  return levels_.at(static_cast<std::size_t>(level)).probes.count(k) > 0;
}

bool CascadesPlanner::has_data(int level, const Key& k) const {
  const auto& m = levels_.at(static_cast<std::size_t>(level)).probes;
  auto it = m.find(k);
  return it != m.end() && it->second.has_data;
}

std::optional<glm::dvec3> CascadesPlanner::capture_point(int level, const Key& k) const {
  const auto& m = levels_.at(static_cast<std::size_t>(level)).probes;
  auto it = m.find(k);
  if (it == m.end()) return std::nullopt;
  return it->second.position;
}

std::optional<Sh9Rgb> CascadesPlanner::value(int level, const Key& k) const {
  const auto& m = levels_.at(static_cast<std::size_t>(level)).probes;
  auto it = m.find(k);
  if (it == m.end() || !it->second.has_data) return std::nullopt;
  return it->second.value;
}

CascadesPlanner::Probe* CascadesPlanner::find(const Ref& r) {
  auto& m = levels_[static_cast<std::size_t>(r.level)].probes;
  auto it = m.find(r.key);
  return it == m.end() ? nullptr : &it->second;
}

void CascadesPlanner::place_window(Level& lv, const glm::dvec3& focus, const FrameContext& ctx) {
  const WorldQueries* world = ctx.world;
  const bool have_ground = world != nullptr && static_cast<bool>(world->ground_height);
  const bool have_surface = world != nullptr && static_cast<bool>(world->surface_height);
  auto ground = [&](double x, double y) { return have_ground ? world->ground_height(x, y) : 0.0; };
  auto surface = [&](double x, double y) {
    return have_surface ? world->surface_height(x, y) : ground(x, y);
  };

  Key c{std::llround(focus.x / lv.s), std::llround(focus.y / lv.s), lv.centre[2]};
  const double target_k =
      (ground(static_cast<double>(c[0]) * lv.s, static_cast<double>(c[1]) * lv.s) + height_m_) /
      lv.vs;
  if (!lv.placed || ctx.camera_cut || std::abs(target_k - static_cast<double>(c[2])) > 0.75) {
    c[2] = std::llround(target_k);
  }
  if (lv.placed && c == lv.centre) return;
  lv.placed = true;
  lv.centre = c;
  const Key n{nx_, ny_, nz_};
  for (int a = 0; a < 3; ++a) {
    lv.lo[a] = c[a] - (n[a] - 1) / 2;
    lv.hi[a] = lv.lo[a] + n[a] - 1;
  }
  // Keep the probes still inside (their data survives the scroll), classify the new slab.
  std::map<Key, Probe> next;
  for (Key k{lv.lo[0], 0, 0}; k[0] <= lv.hi[0]; ++k[0]) {
    for (k[1] = lv.lo[1]; k[1] <= lv.hi[1]; ++k[1]) {
      for (k[2] = lv.lo[2]; k[2] <= lv.hi[2]; ++k[2]) {
        if (auto it = lv.probes.find(k); it != lv.probes.end()) {
          next.emplace(k, it->second);
          continue;
        }
        const glm::dvec3 p{static_cast<double>(k[0]) * lv.s, static_cast<double>(k[1]) * lv.s,
                           static_cast<double>(k[2]) * lv.vs};
        const double floor_z = free_height(surface, p.x, p.y) + clearance_m_;
        Probe q;
        q.position = p;
        if (p.z < floor_z) {
          if (floor_z - p.z > kMaxRelocation * lv.vs || !std::isfinite(floor_z)) {
            faces_saved_ += 6;  // inactive (classification)
            continue;
          }
          q.position.z = floor_z;  // relocation
          ++relocated_;
        }
        next.emplace(k, q);
      }
    }
  }
  lv.probes = std::move(next);
}

std::vector<CaptureRequest> CascadesPlanner::plan(const FrameContext& ctx) {
  pending_.clear();  // anything neither started nor refused last frame never started
  now_ = ctx.time;
  focus_ = make_focus(ctx, prediction_);
  for (Level& lv : levels_) place_window(lv, focus_.ahead, ctx);
  if (ctx.startable_captures <= 0) return {};

  // Priority: (never captured first, then by score), score = distance for never-captured
  // (smaller first), -age / (1 + distance / level spacing) otherwise; ties finer level first,
  // then by lattice index.
  struct Candidate {
    bool captured;
    double score;
    Ref ref;
    glm::dvec3 position;
    bool operator<(const Candidate& o) const {
      if (captured != o.captured) return !captured;
      if (score != o.score) return score < o.score;
      return ref < o.ref;
    }
  };
  std::vector<Candidate> cands;
  for (std::size_t l = 0; l < levels_.size(); ++l) {
    const Level& lv = levels_[l];
    for (const auto& [k, q] : lv.probes) {
      if (q.in_flight) continue;
      const double d = focus_.distance(q.position);
      const Ref r{static_cast<int>(l), k};
      if (!q.has_data) {
        cands.push_back({false, d, r, q.position});
      } else {
        cands.push_back({true, -(now_ - q.last_request) / (1.0 + d / lv.s), r, q.position});
      }
    }
  }
  std::sort(cands.begin(), cands.end());
  // One request per distinct capture point: probes of other levels at the same point (the
  // lattices nest) ride along with it.
  const auto limit = static_cast<std::size_t>(ctx.startable_captures);
  std::map<std::array<double, 3>, std::size_t> chosen;  // capture point -> index in out
  std::vector<CaptureRequest> out;
  for (const Candidate& c : cands) {
    const std::array<double, 3> at{c.position.x, c.position.y, c.position.z};
    if (auto it = chosen.find(at); it != chosen.end()) {
      pending_[out[it->second].tag].push_back(c.ref);
      continue;
    }
    if (out.size() >= limit) continue;
    const std::uint64_t tag = next_tag_++;
    chosen.emplace(at, out.size());
    pending_[tag].push_back(c.ref);
    out.push_back({c.position, tag});
  }
  return out;
}

void CascadesPlanner::started(std::uint64_t tag) {
  auto it = pending_.find(tag);
  if (it == pending_.end()) return;
  for (const Ref& r : it->second) {
    if (Probe* q = find(r)) {
      q->in_flight = true;
      q->last_request = now_;
    }
  }
  in_flight_[tag] = std::move(it->second);
  pending_.erase(it);
}

void CascadesPlanner::refused(std::uint64_t tag) { pending_.erase(tag); }

void CascadesPlanner::deliver(const FinishedProbe& probe) {
  auto f = in_flight_.find(probe.tag);
  if (f == in_flight_.end()) return;
  const std::vector<Ref> refs = std::move(f->second);
  in_flight_.erase(f);
  const Sh9Rgb fresh = format_.store(probe.sh);
  for (const Ref& r : refs) {
    Probe* q = find(r);
    if (q == nullptr) continue;  // scrolled out of its window while it was rendered
    // A newer capture of the same probe may still be in flight; this one is still fresh data.
    q->in_flight = std::any_of(in_flight_.begin(), in_flight_.end(), [&](const auto& kv) {
      return std::find(kv.second.begin(), kv.second.end(), r) != kv.second.end();
    });
    q->target = fresh;
    q->target_time = probe.requested_time;
    q->tag = probe.tag;
    if (!q->has_data && fade_in_) {
      // fade_in: start from what lookups here showed (finer/coarser levels, neighbours).
      const LookupResult before = lookup(q->position);
      if (before.contributor_count > 0) {
        q->has_data = true;
        q->value = format_.store(before.sh);
        q->value_time = before.data_time;
        q->blending = !(q->value == fresh);
        q->remaining = 1.0;
        continue;
      }
    }
    if (!q->has_data) {
      // Newly scrolled in: no hysteresis (RTXGI sets it to 0 for a probe that was black).
      q->has_data = true;
      q->value = fresh;
      q->value_time = probe.requested_time;
      q->blending = false;
    } else {
      q->blending = !(q->value == fresh);
      q->remaining = 1.0;
    }
  }
}

void CascadesPlanner::update(const FrameContext& ctx) {
  // The time since the last update (the frame's dt on the first), whatever plan() saw.
  const double dt = std::isnan(last_update_) ? ctx.dt : std::max(0.0, ctx.time - last_update_);
  last_update_ = ctx.time;
  now_ = ctx.time;
  for (Level& lv : levels_) {
    for (auto& [k, q] : lv.probes) {
      if (!q.blending) continue;
      const double f = ddgi_blend_fraction(q.value, q.target, dt, blend_);
      q.remaining *= 1.0 - f;
      if (q.remaining < kBlendEnd || f >= 1.0) {
        q.value = q.target;
        q.value_time = q.target_time;
        q.blending = false;
        continue;
      }
      q.value = format_.store(sh_lerp(q.value, q.target, static_cast<float>(f)));
      q.value_time += f * (q.target_time - q.value_time);
    }
  }
}

bool CascadesPlanner::inside(const Level& lv, const glm::dvec3& p) const {
  if (lv.probes.empty()) return false;
  const std::array<double, 3> cell{lv.s, lv.s, lv.vs};
  for (int a = 0; a < 3; ++a) {
    const double u = p[a] / cell[a];
    if (!(u >= static_cast<double>(lv.lo[a]) && u <= static_cast<double>(lv.hi[a]))) return false;
  }
  return true;
}

double CascadesPlanner::edge_blend(const Level& lv, const glm::dvec3& p) const {
  if (blend_cells_ <= 0.0) return 0.0;
  double e = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 2; ++a) {  // horizontal edges only: the clipmap's scroll directions
    const double u = p[a] / lv.s;
    e = std::min({e, u - static_cast<double>(lv.lo[a]), static_cast<double>(lv.hi[a]) - u});
  }
  return std::clamp(1.0 - e / blend_cells_, 0.0, 1.0);
}

std::optional<CascadesPlanner::LevelAnswer> CascadesPlanner::level_answer(
    const Level& lv, const glm::dvec3& p) const {
  if (lv.probes.empty()) return std::nullopt;
  const std::array<double, 3> cell{lv.s, lv.s, lv.vs};
  std::array<std::int64_t, 3> i0{};
  std::array<double, 3> f{};
  glm::dvec3 clamped{0.0};
  for (int a = 0; a < 3; ++a) {
    const double u =
        std::clamp(p[a] / cell[a], static_cast<double>(lv.lo[a]), static_cast<double>(lv.hi[a]));
    clamped[a] = u * cell[a];
    i0[a] = std::min(static_cast<std::int64_t>(std::floor(u)), std::max(lv.lo[a], lv.hi[a] - 1));
    f[a] = std::clamp(u - static_cast<double>(i0[a]), 0.0, 1.0);
  }
  const double outside = glm::length(p - clamped);
  if (!std::isfinite(outside)) return std::nullopt;

  struct Corner {
    const Probe* probe;
    double w;
  };
  std::array<Corner, 8> corners{};
  int n = 0;
  double total = 0.0;
  for (int c = 0; c < 8; ++c) {
    const Key k{i0[0] + (c & 1), i0[1] + ((c >> 1) & 1), i0[2] + ((c >> 2) & 1)};
    auto it = lv.probes.find(k);
    if (it == lv.probes.end() || !it->second.has_data) continue;
    double w = 1.0;
    for (int a = 0; a < 3; ++a) w *= ((c >> a) & 1) ? f[a] : 1.0 - f[a];
    corners[static_cast<std::size_t>(n++)] = {&it->second, w};
    total += w;
  }
  if (n == 0) return std::nullopt;
  if (total > 0.0) {
    n = static_cast<int>(std::remove_if(corners.begin(), corners.begin() + n,
                                        [](const Corner& c) { return c.w <= 0.0; }) -
                         corners.begin());
  } else {
    // p sits on the face of probes without data: share equally among those with data.
    for (int c = 0; c < n; ++c) corners[static_cast<std::size_t>(c)].w = 1.0;
    total = n;
  }
  LevelAnswer a;
  for (int c = 0; c < n; ++c) {
    const Corner& k = corners[static_cast<std::size_t>(c)];
    const double w = k.w / total;
    a.sh += k.probe->value * static_cast<float>(w);
    a.data_time += w * k.probe->value_time;
    a.contributors[static_cast<std::size_t>(c)] = {k.probe->tag, static_cast<float>(w)};
  }
  a.count = n;
  a.outside = outside;
  return a;
}

LookupResult CascadesPlanner::nearest_fallback(const glm::dvec3& p) const {
  const Probe* best = nullptr;
  double best_d = std::numeric_limits<double>::infinity();
  for (const Level& lv : levels_) {  // ties: the finer level, the lower lattice index
    for (const auto& [k, q] : lv.probes) {
      if (!q.has_data) continue;
      const double d = glm::distance(q.position, p);
      if (d < best_d) {
        best_d = d;
        best = &q;
      }
    }
  }
  if (best == nullptr) return default_ambient_lookup();
  LookupResult r;
  r.fell_back = true;
  r.sh = best->value;
  r.contributors[0] = {best->tag, 1.0f};
  r.contributor_count = 1;
  r.spacing_m = best_d;
  r.data_time = best->value_time;
  return r;
}

LookupResult CascadesPlanner::lookup(const glm::dvec3& p) const {
  auto to_result = [](const LevelAnswer& a, double spacing) {
    LookupResult r;
    r.sh = a.sh;
    r.data_time = a.data_time;
    r.contributors = a.contributors;
    r.contributor_count = a.count;
    r.fell_back = false;
    r.spacing_m = spacing;
    return r;
  };
  for (std::size_t l = 0; l < levels_.size(); ++l) {
    const Level& lv = levels_[l];
    if (!inside(lv, p)) continue;
    const auto fine = level_answer(lv, p);
    if (!fine) continue;
    const double w = l + 1 < levels_.size() ? edge_blend(lv, p) : 0.0;
    std::optional<LevelAnswer> coarse;
    if (w > 0.0 && inside(levels_[l + 1], p)) coarse = level_answer(levels_[l + 1], p);
    if (!coarse) return to_result(*fine, lv.s);
    // Blend into the next coarser level; merge the contributors (same tag: one entry).
    const double s2 = levels_[l + 1].s;
    LookupResult r;
    r.sh = fine->sh * static_cast<float>(1.0 - w) + coarse->sh * static_cast<float>(w);
    r.data_time = (1.0 - w) * fine->data_time + w * coarse->data_time;
    r.spacing_m = (1.0 - w) * lv.s + w * s2;
    std::map<std::uint64_t, double> merged;
    for (int c = 0; c < fine->count; ++c) {
      const auto& k = fine->contributors[static_cast<std::size_t>(c)];
      merged[k.tag] += (1.0 - w) * k.weight;
    }
    for (int c = 0; c < coarse->count; ++c) {
      const auto& k = coarse->contributors[static_cast<std::size_t>(c)];
      merged[k.tag] += w * k.weight;
    }
    std::vector<Contributor> all;
    for (const auto& [tag, weight] : merged) {
      if (weight > 0.0) all.push_back({tag, static_cast<float>(weight)});
    }
    std::stable_sort(all.begin(), all.end(), [](const Contributor& a, const Contributor& b) {
      return a.weight > b.weight;
    });
    if (all.size() > r.contributors.size()) all.resize(r.contributors.size());
    double kept = 0.0;
    for (const auto& c : all) kept += c.weight;
    for (std::size_t c = 0; c < all.size(); ++c) {
      r.contributors[c] = {all[c].tag, static_cast<float>(all[c].weight / kept)};
    }
    r.contributor_count = static_cast<int>(all.size());
    return r;
  }
  // Outside every window (or no level containing p holds data around it): the coarsest
  // window, clamped, if p is outside it; else the nearest probe with data.
  if (!levels_.empty()) {
    const Level& lv = levels_.back();
    if (!inside(lv, p)) {
      if (const auto a = level_answer(lv, p)) {
        LookupResult r = to_result(*a, lv.s + a->outside);
        r.fell_back = a->outside > 1e-9;
        return r;
      }
    }
  }
  return nearest_fallback(p);
}

PlannerStats CascadesPlanner::stats() const {
  PlannerStats s;
  std::int64_t sets = 0;
  std::size_t nodes = 0;
  for (const Level& lv : levels_) {
    nodes += lv.probes.size();
    for (const auto& [k, q] : lv.probes) {
      if (q.has_data) ++sets;
      if (q.blending) ++sets;  // the target of a blend
    }
  }
  s.live_probes = sets;
  s.nodes = static_cast<std::int64_t>(nodes);
  // Sets count in their storage format (not the in-memory Sh9Rgb copies in Probe twice);
  // structure: map nodes for probes and for captures (one Ref per level served).
  const std::size_t probe_node =
      sizeof(Key) + sizeof(Probe) - 2 * sizeof(Sh9Rgb) + kMapNodeOverhead;
  std::size_t tag_bytes = 0;
  for (const auto* m : {&pending_, &in_flight_}) {
    for (const auto& [tag, refs] : *m) {
      tag_bytes += sizeof(std::uint64_t) + sizeof(std::vector<Ref>) + kMapNodeOverhead +
                   refs.size() * sizeof(Ref);
    }
  }
  s.bytes = static_cast<std::int64_t>(static_cast<std::size_t>(sets) * format_.bytes_per_set() +
                                      nodes * probe_node + tag_bytes);
  return s;
}

void CascadesPlanner::describe_nodes(std::vector<ProbeNodeView>& out) const {
  for (std::size_t l = 0; l < levels_.size(); ++l) {
    for (const auto& [k, q] : levels_[l].probes) {
      ProbeNodeView v;
      v.centre = q.position;
      v.depth = static_cast<int>(l);
      v.has_data = q.has_data;
      v.in_flight = q.in_flight;
      v.age_s = q.has_data ? now_ - q.value_time : 0.0;
      if (q.has_data) v.sh = q.value;
      out.push_back(v);
    }
  }
}

}  // namespace ambisim
