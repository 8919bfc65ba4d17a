#include "policies/ambisim/demand_planner.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <glm/geometric.hpp>

#include "policies/core/default_ambient.h"
#include "policies/core/solid_clearance.h"

namespace ambisim {
namespace {

// Probes delivered between index rebuilds, scanned linearly by queries until the next.
constexpr std::size_t kUnindexedTail = 32;
// Bump weight below which a lookup mixes in the far field. With the tail scan
// (far_field = scan): 0.1, about 1.24 spacings from the nearest probe, beyond the gaps the
// planner leaves between the probes it places (a point midway between two probes one spacing
// apart weighs 1.6); the tail there is the nearest probes' value, so a narrow ramp is enough.
constexpr double kTailConfidence = 0.1;
// With the pyramid: 1, one probe's full bump. The pyramid's value is a 16 m cell's average, so
// it must enter across the bump's whole reach: with 0.1 a receiver crossing the 0.8 m ramp at
// the edge moved from the local value to the average within a frame or two, and viewed pops
// per minute on the kernel sweep rose from 7.8 (the scan) to 23.1 on forest_edge and from
// 0.76 to 2.34 on motorway; with 1 they are 2.6 and 0.75.
constexpr double kPyramidConfidence = 1.0;

// The largest change between two coefficient sets as a log ratio of irradiance, over the six
// axis normals and the three channels (channels darker than 1% of the brightest are lifted to
// it, so that a near-black channel does not dominate).
double log_change(const Sh9Rgb& a, const Sh9Rgb& b) {
  static const glm::dvec3 kAxes[] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                     {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
  Rgb ea[6], eb[6];
  double top = 0.0;
  for (int k = 0; k < 6; ++k) {
    ea[k] = sh_irradiance(a, kAxes[k]);
    eb[k] = sh_irradiance(b, kAxes[k]);
    for (int c = 0; c < 3; ++c) top = std::max({top, double(ea[k][c]), double(eb[k][c])});
  }
  const double floor = std::max(1e-12, 0.01 * top);
  double worst = 0.0;
  for (int k = 0; k < 6; ++k) {
    for (int c = 0; c < 3; ++c) {
      const double x = std::max(double(ea[k][c]), floor), y = std::max(double(eb[k][c]), floor);
      worst = std::max(worst, std::abs(std::log(x / y)));
    }
  }
  return worst;
}

// The scene's light level: the sun's and the sky's irradiance on a horizontal surface, per
// channel, from what the engine knows of its time of day and weather (never of a point).
Rgb scene_light(const LightingInfo& info) {
  Rgb e = sh_irradiance(info.sky_sh, {0.0, 0.0, 1.0});
  if (info.sun_on) e += info.sun_irradiance * static_cast<float>(std::max(info.sun_dir.z, 0.0));
  return glm::max(e, Rgb(1e-9f));
}

double luminance_l00(const Sh9Rgb& sh) { return luminance(sh.c[0]); }

// Whether x may lie nearer to c than best: false only when its squared distance exceeds best^2
// (widened far past rounding), so that a square root is taken only where it can matter.
bool may_beat(const glm::dvec3& x, const glm::dvec3& c, double best) {
  const glm::dvec3 v = x - c;
  return !(v.x * v.x + v.y * v.y + v.z * v.z > best * best * (1.0 + 1e-9));
}

// best, or x's distance to c where that is shorter.
double nearer_than(const glm::dvec3& x, const glm::dvec3& c, double best) {
  return may_beat(x, c, best) ? std::min(best, glm::distance(x, c)) : best;
}

}  // namespace

PlannerInfo DemandPlanner::info() {
  std::vector<ParamSpec> specs = {
      number_param("min_spacing_m", 3.0, Range::positive(), "probe spacing next to the camera (m)"),
      number_param("spacing_per_m", 0.03, Range::closed(0.0, 10.0),
                   "spacing grows by this much per metre of distance from the predicted camera"),
      number_param("max_distance_m", 160.0, Range::positive(),
                   "no captures farther than this from the camera; probes beyond 1.5x fade out"),
      number_param("height_m", 1.2, Range::non_negative(),
                   "height above the ground of path and ring captures"),
      number_param("fade_s", 0.4, Range::non_negative(),
                   "a new probe enters weights and values over this time; leaving ones too"),
      number_param("lifetime_s", 60.0, Range::positive(), "probes are re-captured after this"),
      integer_param("max_probes", 256, Range::closed(1, 1e7), "probes kept (farthest leave)"),
      number_param("lookahead_s", 0.3, Range::closed(0.0, 10.0),
                   "prediction beyond the capture latency"),
      bool_param("route", true, "predict along the road when the camera is on it"),
      choice_param("priority", "need", {"need", "distance"},
                   "objects by need (worst-served first) or by distance to the camera"),
      number_param("fade_rate", 2.0, Range::non_negative(),
                   "a new probe fades in no faster than this change of log irradiance per "
                   "second (0 = always fade_s)"),
      number_param("fade_max_s", 2.0, Range::non_negative(), "longest fade-in of a new probe"),
      bool_param("budget_spacing", true,
                 "below 1 face per frame the near spacing grows as 1 / sqrt(faces per frame), "
                 "up to 4 m: as many probes per area as the budget sustains"),
      bool_param("adapt", true,
                 "halve the spacing where a new probe disagrees with its neighbours"),
      number_param("adapt_rel", 0.25, Range::positive(),
                   "relative brightness disagreement that counts as a fast colour change"),
      choice_param("refresh", "error", {"error", "lifetime"},
                   "when the light changes, refresh probes by expected error (drift) or only "
                   "after lifetime_s"),
      number_param("refresh_drift", 0.04, Range::positive(),
                   "expected relative change of a probe's light that makes it due for a "
                   "refresh (0.04: about 1 dE00 at mid-grey)"),
      bool_param("rescale", true,
                 "between refreshes, scale a probe's sun and sky light by the scene's light "
                 "level now over the level at its capture (twilight dims everything alike)"),
      bool_param("learn_sensitivity", true,
                 "scale the world's rate at a probe by how much its light changed at its last "
                 "refresh for the drift predicted (0.1 to 1): a probe in shadow does not "
                 "follow the sun's dimming"),
      bool_param("kernel_tail", false,
                 "the kernel of the first version: a faint 1e-4 / (1 + u^4) tail beyond the "
                 "bump, so every probe contributes everywhere and a lookup scans all of them "
                 "(no index); kept to measure what the compact kernel costs"),
      choice_param("far_field", "pyramid", {"pyramid", "scan"},
                   "beyond the bumps' reach: `pyramid`, the pull-push far field (a few cells "
                   "per level, whatever the number of probes); `scan`, the previous version's "
                   "faint tail 1 / (1 + u^4) of every probe, a linear scan (fewer pops where "
                   "probes churn, docs/PERFORMANCE.md section 6)"),
      bool_param("lamp_layer", true,
                 "near street lamps, capture their light as a second, additive set scaled by "
                 "the lamps' state (12 faces a capture): a switch costs no recapture")};
  // fp16 by default: measured on four scenarios it moves p95 by <= 0.01 dE00 and saves a third
  // of the memory (README, "Model no more than a scene needs").
  for (auto& s : coefficient_format_params("fp16")) specs.push_back(s);
  return {"ambisim",
          "ambisim's own: demand-driven captures at receivers and the predicted path, "
          "distance-graded spacing, faded interpolation patterns",
          std::move(specs),
          [](const PlannerParams& p) { return std::make_unique<DemandPlanner>(p); }};
}

DemandPlanner::DemandPlanner(const PlannerParams& params)
    : params_(params),
      format_(coefficient_format_from(params)),
      min_spacing_(params.number("min_spacing_m")),
      spacing_per_m_(params.number("spacing_per_m")),
      max_distance_(params.number("max_distance_m")),
      height_(params.number("height_m")),
      fade_s_(params.number("fade_s")),
      lifetime_s_(params.number("lifetime_s")),
      max_probes_(static_cast<std::size_t>(params.integer("max_probes"))),
      by_need_(params.choice("priority") == "need"),
      adapt_(params.boolean("adapt")),
      budget_spacing_(params.boolean("budget_spacing")),
      fade_rate_(params.number("fade_rate")),
      fade_max_s_(params.number("fade_max_s")),
      adapt_de_(params.number("adapt_rel")),
      refresh_by_error_(params.choice("refresh") == "error"),
      refresh_drift_(params.number("refresh_drift")),
      rescale_(params.boolean("rescale")),
      learn_(params.boolean("learn_sensitivity")),
      lamp_layer_(params.boolean("lamp_layer")),
      kernel_tail_(params.boolean("kernel_tail")),
      far_scan_(params.choice("far_field") == "scan"),
      default_sh_(default_ambient_sh()) {
  prediction_.enabled = true;
  prediction_.lookahead_s = params.number("lookahead_s");
  prediction_.route = params.boolean("route");
}

double DemandPlanner::required_spacing(double distance_m) const {
  return std::max(min_spacing_ * budget_scale_, spacing_per_m_ * distance_m);
}

void DemandPlanner::set_budget(double faces_per_frame) {
  budget_scale_ = 1.0;
  if (budget_spacing_ && faces_per_frame > 0.0 && faces_per_frame < 1.0) {
    // Never coarser than 4 m, the near spacing of the coverage rule.
    budget_scale_ = std::max(1.0, std::min(std::sqrt(1.0 / faces_per_frame), 4.0 / min_spacing_));
  }
}

double DemandPlanner::fade_in_fraction(const Probe& q) const {
  if (q.fade_in <= 0.0) return 1.0;
  if (q.fade_in_start < 0.0) return 0.0;
  return std::clamp((now_ - q.fade_in_start) / q.fade_in, 0.0, 1.0);
}

double DemandPlanner::presence(const Probe& q) const {
  double f = q.weight_fades_in ? fade_in_fraction(q) : 1.0;
  if (q.fade_out_start >= 0.0) {
    if (fade_s_ <= 0.0) return 0.0;
    f *= std::clamp(1.0 - (now_ - q.fade_out_start) / fade_s_, 0.0, 1.0);
  }
  return f;
}

Sh9Rgb DemandPlanner::stored(const Probe& q) const {
  return q.full >= 0 ? pool_.sets[static_cast<std::size_t>(q.full)] : from_half(q.half);
}

void DemandPlanner::add_stored(const Probe& q, const Rgb& k, Sh9Rgb& sum) const {
  if (q.full < 0) {
    sh_add_scaled(sum, q.half, k);
    return;
  }
  const Sh9Rgb& sh = pool_.sets[static_cast<std::size_t>(q.full)];
  for (int i = 0; i < kShCount; ++i)
    sum.c[static_cast<std::size_t>(i)] += sh.c[static_cast<std::size_t>(i)] * k;
}

void DemandPlanner::store(Probe& q, const Sh9Rgb& sh) {
  const Sh9Rgb s = format_.store(sh);
  if (format_.half) {
    q.half = to_half(s);
    return;
  }
  if (q.full >= 0) {
    pool_.sets[static_cast<std::size_t>(q.full)] = s;
  } else {
    q.full = pool_.add(s);
  }
}

Sh9Rgb DemandPlanner::current(const Probe& q) const {
  Sh9Rgb now = stored(q);
  if (rescale_) {
    const Rgb k = light_now_ / q.light;
    for (auto& c : now.c) c *= k;
  }
  if (q.has_lamps() && lamp_level_ > 0.0) {
    now += pool_.sets[static_cast<std::size_t>(q.lamps)] * static_cast<float>(lamp_level_);
  }
  return now;
}

Sh9Rgb DemandPlanner::shown(const Probe& q) const {
  const Sh9Rgb now = current(q);
  // A leaving probe keeps its value; an arriving or refreshed one blends from the old.
  const double fin = q.fade_out_start >= 0.0 ? 1.0 : fade_in_fraction(q);
  if (fin >= 1.0 || q.from < 0) return now;
  return sh_lerp(pool_.sets[static_cast<std::size_t>(q.from)], now, static_cast<float>(fin));
}

void DemandPlanner::add_shown(const Probe& q, float w, Sh9Rgb& sum) const {
  const double fin = q.fade_out_start >= 0.0 || q.from < 0 ? 1.0 : fade_in_fraction(q);
  const float a = static_cast<float>(fin);
  Rgb k(w * a);
  if (rescale_) k *= light_now_ / q.light;
  add_stored(q, k, sum);
  if (q.has_lamps() && lamp_level_ > 0.0) {
    const float l = w * a * static_cast<float>(lamp_level_);
    const Sh9Rgb& lamps = pool_.sets[static_cast<std::size_t>(q.lamps)];
    for (int i = 0; i < kShCount; ++i)
      sum.c[static_cast<std::size_t>(i)] += lamps.c[static_cast<std::size_t>(i)] * l;
  }
  if (a < 1.0f) {
    const float b = w * (1.0f - a);
    const Sh9Rgb& from = pool_.sets[static_cast<std::size_t>(q.from)];
    for (int i = 0; i < kShCount; ++i)
      sum.c[static_cast<std::size_t>(i)] += from.c[static_cast<std::size_t>(i)] * b;
  }
}

DemandPlanner::Look DemandPlanner::look_of(const Probe& q) const {
  Look l;
  l.presence = static_cast<float>(presence(q));
  const double fin = q.fade_out_start >= 0.0 || q.from < 0 ? 1.0 : fade_in_fraction(q);
  l.scale = Rgb(static_cast<float>(fin));
  if (rescale_) l.scale *= light_now_ / q.light;
  l.plain = !(q.has_lamps() && lamp_level_ > 0.0) && fin >= 1.0;
  return l;
}

std::int32_t DemandPlanner::SetPool::add(const Sh9Rgb& sh) {
  if (!free.empty()) {
    const std::int32_t slot = free.back();
    free.pop_back();
    sets[static_cast<std::size_t>(slot)] = sh;
    return slot;
  }
  sets.push_back(sh);
  return static_cast<std::int32_t>(sets.size() - 1);
}

void DemandPlanner::SetPool::release(std::int32_t& slot) {
  if (slot < 0) return;
  free.push_back(slot);
  slot = -1;
}

bool DemandPlanner::near_lamps(const glm::dvec3& p) const {
  const double r = lamp_reach_m_ + min_spacing_;
  for (const auto& l : lamps_) {
    const double dx = l.x - p.x, dy = l.y - p.y;
    if (dx * dx + dy * dy <= r * r) return true;
  }
  return false;
}

bool DemandPlanner::wants_lamp_layer(const glm::dvec3& p) const {
  return lamp_layers_ && near_lamps(p);
}

DemandPlanner::Probe* DemandPlanner::find_probe(std::uint64_t tag) {
  for (auto& q : probes_) {
    if (q.tag == tag) return &q;
  }
  return nullptr;
}

double DemandPlanner::kernel(const Probe& q, double d2) const {
  // Smooth, and continuous everywhere: a compact bump over 1.5 spacings (neighbours one
  // spacing apart overlap, so weights change continuously as a receiver moves). Compact so
  // that a spatial index finds every contributor: an earlier faint tail (1e-4 / (1 + u^4))
  // reached every probe of the level and made each lookup a scan of all of them
  // (docs/PERFORMANCE.md gives what cutting it cost in accuracy).
  const double r = support_radius(q);
  const double u2 = d2 / (r * r);
  const double bump = u2 < 1.0 ? (1.0 - u2) * (1.0 - u2) : 0.0;
  return kernel_tail_ ? bump + 1e-4 / (1.0 + u2 * u2) : bump;
}

bool DemandPlanner::interpolate(const glm::dvec3& p, Sh9Rgb& out, LookupResult* meta,
                                bool reference, FarField::CornerMemo* memo) const {
  // Two blends: the bumps (compact, found by the index) and, only where the bumps' total weight
  // is below bump_confidence(), the far field (policies/ambisim/far_field.h: the probes' pull-push
  // pyramid, a few cells read per level whatever the number of probes). The answer is
  // alpha x bumps + (1 - alpha) x far field with alpha = min(1, bump total / bump_confidence()):
  // continuous everywhere and in time (both blends are, and alpha is), so a receiver crossing
  // the edge of the probes' reach does not pop, as it did with the nearest probe there.
  struct Candidate {
    double weight;
    double d2;
    std::size_t index;
  };
  std::array<Candidate, 8> top{};
  int count = 0;
  auto keep = [&](const Candidate& c) {
    // The 8 heaviest as the reported contributors (ties: the lower index, whatever the
    // visiting order, so the index and the scan agree).
    auto lighter = [](const Candidate& x, const Candidate& y) {
      return x.weight < y.weight || (x.weight == y.weight && x.index > y.index);
    };
    if (count < 8) {
      top[static_cast<std::size_t>(count++)] = c;
    } else {
      auto lightest = std::min_element(top.begin(), top.end(), lighter);
      if (lighter(*lightest, c)) *lightest = c;
    }
  };
  double total = 0.0, time_sum = 0.0;
  Sh9Rgb sum;
  // A contributor's weight into the totals and the top 8 (its value is already in sum).
  auto take = [&](std::size_t i, double w, double d2) {
    total += w;
    time_sum += w * probes_[i].data_time;
    keep({w, d2, i});
  };
  auto visit = [&](std::size_t i) {
    const Probe& q = probes_[i];
    const glm::dvec3 v = q.position - p;
    const double d2 = glm::dot(v, v);
    const double w = bump_weight(q, d2);
    if (w <= 0.0) return;
    // The value itself also enters gradually, from what was shown here before.
    add_shown(q, static_cast<float>(w), sum);
    take(i, w, d2);
  };
  // The indexed path reads the baked looks (the same terms as bump_weight and add_shown,
  // rounded once to float); the reference recomputes them per probe.
  auto visit_indexed = [&](std::size_t i) {
    const Probe& q = probes_[i];
    const glm::dvec3 v = q.position - p;
    const double d2 = glm::dot(v, v);
    const double r = support_radius(q);
    if (d2 >= r * r) return;
    const Look& l = looks_[i];
    const double w = kernel(q, d2) * static_cast<double>(l.presence);
    if (w <= 0.0) return;
    if (l.plain) {
      add_stored(q, l.scale * static_cast<float>(w), sum);
    } else {
      add_shown(q, static_cast<float>(w), sum);
    }
    take(i, w, d2);
  };
  std::size_t scan_from = 0;
  if (!reference && !kernel_tail_) {
    index_.for_each_candidate(p, visit_indexed);
    scan_from = index_.size();
  }
  for (std::size_t i = scan_from; i < probes_.size(); ++i) visit(i);
  const double alpha = kernel_tail_ ? 1.0 : std::min(1.0, total / bump_confidence());
  double far_cell_m = 0.0;
  FarField::Answer far;
  // The far field's sums are those of the last update(): a probe delivered since (present at
  // once only with fade_s = 0) is in the bumps alone until then.
  if (alpha < 1.0 && (far_scan_   ? scan_tail(p, far)
                      : reference ? evaluate_far_field_reference(p, far)
                                  : far_.evaluate(p, far, memo))) {
    // The bump contributors keep their shares of the mix; the far field's are not probes.
    const double a = total > 0.0 ? alpha / total : 0.0;  // per unit of bump weight
    const float b = static_cast<float>(1.0 - alpha);
    Sh9Rgb mixed;
    for (int k = 0; k < kShCount; ++k) {
      const auto c = static_cast<std::size_t>(k);
      mixed.c[c] = sum.c[c] * static_cast<float>(a) + far.sh.c[c] * b;
    }
    sum = mixed;
    time_sum = time_sum * a + far.data_time * (1.0 - alpha);
    for (int k = 0; k < count; ++k) top[static_cast<std::size_t>(k)].weight *= a;
    far_cell_m = far.cell_m;
    total = 1.0;
  }
  if (total <= 0.0) return false;
  out = sum * static_cast<float>(1.0 / total);
  if (meta) {
    // Heaviest first (insertion sort of at most 8; ties by index for determinism).
    for (int i = 1; i < count; ++i) {
      for (int j = i; j > 0; --j) {
        const Candidate& x = top[static_cast<std::size_t>(j)];
        const Candidate& y = top[static_cast<std::size_t>(j - 1)];
        if (x.weight > y.weight || (x.weight == y.weight && x.index < y.index)) {
          std::swap(top[static_cast<std::size_t>(j)], top[static_cast<std::size_t>(j - 1)]);
        } else {
          break;
        }
      }
    }
    double closest = std::numeric_limits<double>::infinity();
    std::size_t closest_index = top[0].index;
    for (int k = 0; k < count; ++k) {
      meta->contributors[k] = {probes_[top[k].index].tag,
                               static_cast<float>(top[k].weight / total)};
      if (top[k].d2 < closest) {
        closest = top[k].d2;
        closest_index = top[k].index;
      }
    }
    meta->contributor_count = count;
    // The resolution of what answered: the closest contributor's spacing (or twice its
    // distance), and where the far field shares the answer, the span of its trilinear reach.
    meta->spacing_m = 2.0 * far_cell_m;
    if (count > 0) {
      const Probe& q = probes_[closest_index];
      meta->spacing_m = std::max(
          {meta->spacing_m, static_cast<double>(q.spacing * q.detail), 2.0 * std::sqrt(closest)});
    }
    meta->data_time = time_sum / total;
  }
  return true;
}

void DemandPlanner::lookup_into(const glm::dvec3& p, bool reference, FarField::CornerMemo* memo,
                                LookupResult& r) const {
  if (!interpolate(p, r.sh, &r, reference, memo)) {
    r.sh = default_sh_;
    r.fell_back = true;
    r.spacing_m = std::numeric_limits<double>::infinity();
    r.data_time = now_;
  }
}

LookupResult DemandPlanner::lookup_with(const glm::dvec3& p, bool reference) const {
  LookupResult r;
  lookup_into(p, reference, nullptr, r);
  return r;
}

LookupResult DemandPlanner::lookup(const glm::dvec3& p) const { return lookup_with(p, false); }

double DemandPlanner::bump_weight(const Probe& q, double d2) const {
  const double r = support_radius(q);
  if (d2 >= r * r && !kernel_tail_) return 0.0;
  const double f = presence(q);
  return f > 0.0 ? kernel(q, d2) * f : 0.0;
}

bool DemandPlanner::lookup_uses_far_field(const glm::dvec3& p) const {
  if (kernel_tail_) return false;
  double total = 0.0;
  auto visit = [&](std::size_t i) {
    const Probe& q = probes_[i];
    const glm::dvec3 v = q.position - p;
    total += bump_weight(q, glm::dot(v, v));
  };
  index_.for_each_candidate(p, visit);
  for (std::size_t i = index_.size(); i < probes_.size(); ++i) visit(i);
  return total < bump_confidence();
}

LookupResult DemandPlanner::lookup_reference(const glm::dvec3& p) const {
  return lookup_with(p, true);
}

void DemandPlanner::lookup_many(const LookupPoints& points, std::vector<LookupResult>& out) const {
  // Each answer is lookup()'s, bit for bit. A frame's points share the far field's cell blocks
  // (the memo saves their finds), and each result is written in place rather than copied. (A
  // memo of the index's cells was tried as well: its finer cells repeat less, and it made the
  // batch slower, 2.3 -> 2.6 ms at BM_LookupMany/ambisim/10000.)
  out.assign(points.size(), LookupResult{});
  FarField::CornerMemo memo(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    lookup_into({points.x[i], points.y[i], points.z[i]}, false, &memo, out[i]);
  }
}

void DemandPlanner::carry_memos(std::span<const std::int32_t> new_slot, std::size_t tail_from) {
  const auto build = static_cast<std::uint32_t>(index_builds_);
  for (NearestMemo& m : nearest_memo_) {
    if (m.build != build) continue;  // void already: plan() searches the new index
    // The memo's probe is the nearest staying probe of the old index (or none is staying). If
    // it stays, it survives the rebuild (only probes that left are dropped) and its slot moves
    // down with the dropped ones before it; slots keep their order.
    std::int64_t best = -1;
    double best2 = std::numeric_limits<double>::infinity();
    if (m.probe >= 0) {
      const auto old = static_cast<std::size_t>(m.probe);
      const std::int32_t s = new_slot.empty() ? m.probe : new_slot[old];
      if (s < 0 || probes_[static_cast<std::size_t>(s)].fade_out_start >= 0.0) {
        m.build = build - 1;  // it left: void
        continue;
      }
      best = s;
      const glm::dvec3 d = probes_[static_cast<std::size_t>(s)].position - m.at;
      best2 = d.x * d.x + d.y * d.y + d.z * d.z;
    }
    // The tail's slots are all above the old index's: a tie keeps the lower, as nearest() does.
    for (std::size_t i = tail_from; i < probes_.size(); ++i) {
      if (probes_[i].fade_out_start >= 0.0) continue;
      const glm::dvec3 d = probes_[i].position - m.at;
      const double d2 = d.x * d.x + d.y * d.y + d.z * d.z;
      if (d2 < best2) {
        best2 = d2;
        best = static_cast<std::int64_t>(i);
      }
    }
    m = {m.id, m.at, build + 1, static_cast<std::int32_t>(best)};
  }
}

void DemandPlanner::reindex(std::span<const std::int32_t> new_slot) {
  // The probes the old index held, in the new slots: those before the first new slot of the
  // old tail.
  std::size_t tail_from = index_.size();
  if (!new_slot.empty()) {
    tail_from = 0;
    for (std::size_t i = 0; i < index_.size(); ++i) tail_from += new_slot[i] >= 0 ? 1 : 0;
  }
  carry_memos(new_slot, tail_from);
  ++index_builds_;
  std::vector<glm::dvec3> positions(probes_.size());
  std::vector<double> radii(probes_.size());
  for (std::size_t i = 0; i < probes_.size(); ++i) {
    positions[i] = probes_[i].position;
    radii[i] = support_radius(probes_[i]);
  }
  index_.build(positions, radii);
  if (uses_pyramid()) far_.build(positions);
  follow_probes(true);
}

void DemandPlanner::add_far_sums(std::size_t i, FarField::Sums& s) const {
  const Probe& q = probes_[i];
  const double f = presence(q);
  if (f <= 0.0) return;
  add_shown(q, static_cast<float>(f), s.sh);
  s.weight += f;
  s.time += f * q.data_time;
}

double DemandPlanner::bump_confidence() const {
  return far_scan_ ? kTailConfidence : kPyramidConfidence;
}

bool DemandPlanner::scan_tail(const glm::dvec3& p, FarField::Answer& out) const {
  // Every present probe, weighted 1 / (1 + u^4) (u = distance over its support radius): the
  // nearest dominate, as a smooth nearest-probe answer.
  Sh9Rgb sum;
  double total = 0.0, time = 0.0, closest2 = std::numeric_limits<double>::infinity();
  for (const Probe& q : probes_) {
    const double f = presence(q);
    if (f <= 0.0) continue;
    const glm::dvec3 v = q.position - p;
    const double d2 = glm::dot(v, v);
    const double r = support_radius(q);
    const double u2 = d2 / (r * r);
    const double t = f / (1.0 + u2 * u2);
    add_shown(q, static_cast<float>(t), sum);
    total += t;
    time += t * q.data_time;
    closest2 = std::min(closest2, d2);
  }
  if (total <= 0.0) return false;
  out.sh = sum * static_cast<float>(1.0 / total);
  out.data_time = time / total;
  out.cell_m = std::sqrt(closest2);  // twice this is the resolution reported
  return true;
}

void DemandPlanner::follow_probes(bool all) {
  // A probe's look and sums move while it fades in or out, when its value is replaced and with
  // the light: everything else gives what it gave at the last call.
  const bool light_moved = (rescale_ && light_now_ != far_light_) || lamp_level_ != far_lamp_level_;
  const bool pyramid = uses_pyramid();
  looks_.resize(probes_.size());
  far_steady_.resize(probes_.size(), 0);
  const bool each = all || light_moved || now_ < far_time_;
  for (std::size_t i = 0; i < probes_.size(); ++i) {
    const Probe& q = probes_[i];
    // Steady at the last call and not leaving now: still steady (a fade-in's fraction only
    // grows with the clock; a refresh, which starts a new one, clears far_steady_), with the
    // look and sums it had. Skips the fraction's division for most probes of a frame; every
    // other probe's look and sums are redone.
    if (!each && far_steady_[i] && q.fade_out_start < 0.0) continue;
    looks_[i] = look_of(q);
    if (pyramid) far_.mark(i);
    far_steady_[i] = q.fade_out_start < 0.0 && fade_in_fraction(q) >= 1.0 ? 1 : 0;
  }
  far_light_ = light_now_;
  far_lamp_level_ = lamp_level_;
  far_time_ = now_;
  if (pyramid) far_.refill_marked([this](std::size_t i, FarField::Sums& s) { add_far_sums(i, s); });
}

bool DemandPlanner::evaluate_far_field_reference(const glm::dvec3& p, FarField::Answer& out) const {
  std::vector<glm::dvec3> positions(probes_.size());
  for (std::size_t i = 0; i < probes_.size(); ++i) positions[i] = probes_[i].position;
  return FarField::evaluate_reference(
      p, positions, [this](std::size_t i, FarField::Sums& s) { add_far_sums(i, s); }, out);
}

double DemandPlanner::nearest_distance(const glm::dvec3& c, double* detail) const {
  double best = 0.0;
  std::int64_t n = index_.nearest(
      c, [&](std::uint32_t i) -> const glm::dvec3& { return probes_[i].position; },
      [&](std::uint32_t i) { return probes_[i].fade_out_start < 0.0; }, &best);
  nearest_in_tail(c, index_.size(), n, best);
  *detail = n >= 0 ? probes_[static_cast<std::size_t>(n)].detail : 1.0;
  for (const auto* m : {&planned_, &in_flight_}) {
    for (const auto& [tag, f] : *m) best = nearer_than(f.position, c, best);
  }
  return best;
}

void DemandPlanner::nearest_in_tail(const glm::dvec3& c, std::size_t from, std::int64_t& n,
                                    double& best) const {
  // The square root only for probes that may be nearer than the best so far (may_beat): the
  // roots were most of this scan's cost when it covered the whole tail for every object.
  for (std::size_t i = from; i < probes_.size(); ++i) {
    if (probes_[i].fade_out_start >= 0.0 || !may_beat(probes_[i].position, c, best)) continue;
    const double d = glm::distance(probes_[i].position, c);
    if (d < best) {
      best = d;
      n = static_cast<std::int64_t>(i);
    }
  }
}

glm::dvec3 DemandPlanner::capture_point(const FrameContext& ctx, const glm::dvec3& p) const {
  return above_solids(ctx.world, p, kSolidClearance_m);  // never inside a solid
}

std::vector<CaptureRequest> DemandPlanner::plan(const FrameContext& ctx) {
  planned_.clear();
  std::vector<CaptureRequest> out;
  if (!world_known_ && ctx.world != nullptr) {
    world_known_ = true;
    lamps_ = ctx.world->lamp_positions;
    lamp_reach_m_ = ctx.world->lamp_reach_m;
    lamp_layers_ = lamp_layer_ && ctx.world->has_lamps && !lamps_.empty();
  }
  if (ctx.startable_captures <= 0) return out;
  set_budget(ctx.faces_per_frame);
  // The light level the captures planned now will be rendered under (they start this frame).
  Rgb light = light_now_;
  if (ctx.world != nullptr && !ctx.world->lighting_static && ctx.world->lighting) {
    light = scene_light(ctx.world->lighting(ctx.time));
  }
  focus_ = make_focus(ctx, prediction_);
  const double latency = std::isfinite(ctx.capture_latency_s()) ? ctx.capture_latency_s() : 0.0;
  const double horizon = ctx.camera_cut ? 0.0 : latency + prediction_.lookahead_s;
  // Path and ring captures stand where objects stand: on the terrain or the canopy top.
  auto ground = [&](double x, double y) {
    return ctx.world != nullptr && ctx.world->surface_height ? ctx.world->surface_height(x, y)
                                                             : 0.0;
  };
  // Every capture this frame can start is planned: consider() and refresh() do nothing more.
  auto full = [&] { return static_cast<int>(out.size()) >= ctx.startable_captures; };
  auto consider = [&](const glm::dvec3& c) {
    if (full()) return;
    const double d = focus_.distance(c);
    if (d > max_distance_) return;
    double detail = 1.0;
    const double spacing = required_spacing(d);
    const double gap = nearest_distance(c, &detail);
    // Probes stand about one spacing apart: a point needs one when the nearest is farther
    // than half the (locally refined) spacing.
    if (gap <= 0.5 * spacing * detail) return;
    const std::uint64_t tag = next_tag_++;
    const glm::dvec3 at = capture_point(ctx, c);
    planned_[tag] = {at, spacing * detail, ctx.time, 0, 0.0, light};
    out.push_back({at, tag, wants_lamp_layer(at)});
  };
  // A stale probe captured again where it stands.
  auto refresh = [&](Probe& q) {
    if (full()) return;
    const std::uint64_t tag = next_tag_++;
    planned_[tag] = {q.position, q.spacing, ctx.time, q.tag, q.drift, light};
    q.refreshing = true;
    out.push_back({q.position, tag, wants_lamp_layer(q.position)});
  };
  // 1. The objects the game will light, where they will be, by need: the worst-served first
  // (their nearest probe farthest, relative to the spacing they need), so that when objects
  // appear faster than they can be captured (a LOD switch) the budget covers them evenly.
  // Among equally served objects (e.g. none has a probe yet) the nearest to the camera goes
  // first. No object is served before the others just for being nearest: the player's own
  // vehicle flies with the camera, needs a probe every few metres of its flight, and would
  // take the whole budget (forest_edge b1 p95 13.0 with that rule, 6.5 without).
  struct Ranked {
    double need;
    double distance;
    std::size_t index;
  };
  // Only objects a capture could serve are ranked: within max_distance_m and without a probe
  // within half their spacing (consider() would refuse the rest). Leaving the others out changes
  // nothing but the refreshes' place in the order (below): an object refused for a near probe
  // has an urgency of at most 1, so it only lets every stale probe go before the objects after
  // it, which u_refused keeps. Objects out of range take no part (they cannot be served).
  // A probe within a quarter spacing refuses an object whatever the detail factor (>= 0.5).
  std::vector<Ranked> order;
  double u_refused = std::numeric_limits<double>::infinity();  // least urgency of those refused
  auto staying = [&](std::uint32_t i) { return probes_[i].fade_out_start < 0.0; };
  auto position_of = [&](std::uint32_t i) -> const glm::dvec3& { return probes_[i].position; };
  nearest_memo_.resize(receivers_.size());
  // The captures in flight (none planned yet), read by every object: in one array, not a map.
  std::vector<glm::dvec3> pending;
  pending.reserve(planned_.size() + in_flight_.size());
  for (const auto* m : {&planned_, &in_flight_}) {
    for (const auto& [tag, f] : *m) pending.push_back(f.position);
  }
  for (std::size_t i = 0; i < receivers_.size(); ++i) {
    const ReceiverView& r = receivers_[i];
    const glm::dvec3 at = r.position + horizon * r.velocity;
    const double to_camera = glm::distance(r.position, ctx.camera_position);
    const double d = focus_.distance(at);
    if (d > max_distance_) continue;
    const double spacing = required_spacing(d);
    NearestMemo& m = nearest_memo_[i];
    const auto build = static_cast<std::uint32_t>(index_builds_);
    if (!(m.id == r.id && m.at == at && m.build == build && m.probe >= 0 &&
          staying(static_cast<std::uint32_t>(m.probe)))) {
      double ignored = 0.0;
      m = {r.id, at, build,
           static_cast<std::int32_t>(index_.nearest(at, position_of, staying, &ignored))};
    }
    // The nearest indexed probe's squared distance, as the index computes it: within a quarter
    // spacing exactly when any staying indexed probe is (ProbeIndex::any_within).
    double d2 = std::numeric_limits<double>::infinity();
    if (m.probe >= 0) {
      const glm::dvec3 v = probes_[static_cast<std::size_t>(m.probe)].position - at;
      d2 = v.x * v.x + v.y * v.y + v.z * v.z;
    }
    const double quarter = 0.25 * spacing;
    if (d2 <= quarter * quarter) {
      u_refused = std::min(u_refused, 0.5);  // its need is at most 0.25
      continue;
    }
    // The tail: from the memo's nearest while it stays, over the probes delivered since.
    if (m.tail_to == kTailNotScanned ||
        (m.tail_probe >= 0 && !staying(static_cast<std::uint32_t>(m.tail_probe)))) {
      m.tail_to = static_cast<std::uint32_t>(index_.size());
      m.tail_probe = m.probe;
    }
    std::int64_t nearest = m.tail_probe;
    // Its distance as the scan found it: the indexed probe's from d2, a tail probe's by
    // glm::distance, as nearest_in_tail() computes it.
    double gap = nearest == m.probe
                     ? std::sqrt(d2)
                     : glm::distance(probes_[static_cast<std::size_t>(nearest)].position, at);
    nearest_in_tail(at, m.tail_to, nearest, gap);
    m.tail_to = static_cast<std::uint32_t>(probes_.size());
    m.tail_probe = static_cast<std::int32_t>(nearest);
    const double detail = nearest >= 0 ? probes_[static_cast<std::size_t>(nearest)].detail : 1.0;
    for (const glm::dvec3& x : pending) gap = nearer_than(x, at, gap);
    const double need = by_need_ ? gap / (spacing * detail) : -to_camera;
    if (gap <= 0.5 * spacing * detail) {
      u_refused =
          std::min(u_refused, by_need_ ? need / 0.5 : std::numeric_limits<double>::infinity());
      continue;
    }
    order.push_back({need, to_camera, i});
  }
  // The objects are taken in that order until the captures run out, which is after a few
  // (one per frame at the thesis' budget): a heap hands them out in the same order as a full
  // sort (the order is total: indices are unique) for O(n) instead of O(n log n). With 1e3
  // objects the sort took 11 % of BM_FrameReceivers/ambisim's frame samples, and more inlined.
  auto later = [](const Ranked& a, const Ranked& b) {
    if (a.need != b.need) return a.need < b.need;
    if (a.distance != b.distance) return a.distance > b.distance;
    return a.index > b.index;
  };
  std::make_heap(order.begin(), order.end(), later);
  // Stale probes in use (within the capture range), the most stale first. Their urgency,
  // drift over the error tolerated at their distance (refresh_drift near the camera, growing
  // with distance as the spacing does: a far object is small on screen), and an object's,
  // need / 0.5 (its nearest probe in spacings over the half spacing at which it gets one), are
  // both >= 1 when due: the budget goes to the larger.
  std::vector<Ranked> stale;
  const double near_spacing = required_spacing(0.0);
  for (std::size_t i = 0; i < probes_.size(); ++i) {
    const Probe& q = probes_[i];
    if (q.fade_out_start >= 0.0 || q.refreshing) continue;
    // The tolerated error is refresh_drift or more (the spacing grows with distance from its
    // value at the focus), so a probe that drifted less than half of it is not stale: under a
    // static light no probe drifts, and none costs a distance here.
    if (q.drift < 0.5 * refresh_drift_) continue;
    const double d = focus_.distance(q.position);
    if (d > max_distance_) continue;
    const double urgency = q.drift / (refresh_drift_ * required_spacing(d) / near_spacing);
    if (urgency >= 1.0) stale.push_back({urgency, d, i});
  }
  std::sort(stale.begin(), stale.end(), [](const Ranked& a, const Ranked& b) {
    if (a.need != b.need) return a.need > b.need;
    if (a.distance != b.distance) return a.distance < b.distance;
    return a.index < b.index;
  });
  // (Capping the refreshes' share of the captures while objects need probes was tried: at 0.3
  // and 0.5 of the captures day_cycle's viewed p95 was 2.99 and 2.84 against 1.45 uncapped,
  // sunset_drive's and fog_bank's within 0.05.)
  std::size_t next_stale = 0;
  // Once full, the rest of the ranking could plan nothing: stop there.
  while (!order.empty() && !full()) {
    std::pop_heap(order.begin(), order.end(), later);
    const Ranked k = order.back();
    order.pop_back();
    const double urgency = by_need_ ? k.need / 0.5 : std::numeric_limits<double>::infinity();
    while (next_stale < stale.size() && stale[next_stale].need > urgency) {
      refresh(probes_[stale[next_stale++].index]);
    }
    const ReceiverView& r = receivers_[k.index];
    consider(r.position + horizon * r.velocity);
  }
  while (next_stale < stale.size() && stale[next_stale].need > u_refused) {
    refresh(probes_[stale[next_stale++].index]);
  }
  // 2. The camera's predicted path.
  for (double t : {0.0, 0.5, 1.0, 2.0}) {
    const glm::dvec3 p = predict_position(ctx, ctx.camera_cut ? t : horizon + t, prediction_.route,
                                          prediction_.route_snap_m);
    consider({p.x, p.y, ground(p.x, p.y) + height_});
  }
  // 3. Rings around the predicted camera, denser near it.
  for (double r : {6.0, 12.0, 24.0, 48.0}) {
    for (int a = 0; a < 8; ++a) {
      const double phi = 2.0 * std::numbers::pi * a / 8.0;
      const double x = focus_.ahead.x + r * std::cos(phi), y = focus_.ahead.y + r * std::sin(phi);
      consider({x, y, ground(x, y) + height_});
    }
  }
  // Captures left over after every object and the path: the stale probes, the most stale first.
  while (next_stale < stale.size()) refresh(probes_[stale[next_stale++].index]);
  return out;
}

void DemandPlanner::started(std::uint64_t tag) {
  auto it = planned_.find(tag);
  if (it == planned_.end()) return;
  in_flight_[tag] = it->second;
  planned_.erase(it);
}

void DemandPlanner::refused(std::uint64_t tag) {
  auto it = planned_.find(tag);
  if (it == planned_.end()) return;
  if (it->second.refresh_of != 0) {
    if (Probe* q = find_probe(it->second.refresh_of)) q->refreshing = false;
  }
  planned_.erase(it);
}

void DemandPlanner::deliver(const FinishedProbe& probe) {
  auto it = in_flight_.find(probe.tag);
  if (it == in_flight_.end()) return;
  if (it->second.refresh_of != 0) {
    // A refresh: the new value fades in over what the probe showed, in place; its weight stays.
    Probe* q = find_probe(it->second.refresh_of);
    const double it_drift = it->second.drift_at_request;
    const Rgb it_light = it->second.light;
    in_flight_.erase(it);
    if (q == nullptr || q->fade_out_start >= 0.0) return;  // it left meanwhile
    const Sh9Rgb was = shown(*q);
    pool_.release(q->from);
    q->from = pool_.add(was);
    store(*q, probe.sh);
    pool_.release(q->lamps);
    if (probe.has_lamp_layer) q->lamps = pool_.add(format_.store(probe.sh_lamps));
    q->data_time = probe.requested_time;
    q->light = it_light;
    // How much its light changed for the drift predicted: its sensitivity to the world's rate.
    const double observed = log_change(was, current(*q));
    if (learn_ && it_drift > 0.0) {
      const double raw = it_drift / q->sensitivity;
      q->sensitivity =
          static_cast<float>(std::clamp(0.5 * q->sensitivity + 0.5 * observed / raw, 0.1, 1.0));
    }
    // The light went on changing while the capture rendered.
    q->drift = static_cast<float>(std::max(0.0, q->drift - it_drift));
    q->refreshing = false;
    q->weight_fades_in = false;
    q->fade_in_start = -1.0;
    q->fade_in = static_cast<float>(fade_s_);
    if (fade_rate_ > 0.0) {
      q->fade_in = static_cast<float>(std::clamp(log_change(was, current(*q)) / fade_rate_, fade_s_,
                                                 std::max(fade_s_, fade_max_s_)));
    }
    // What lookups read of it changed now, not at the next update().
    const auto slot = static_cast<std::size_t>(q - probes_.data());
    if (slot < looks_.size()) looks_[slot] = look_of(*q);
    if (slot < far_steady_.size()) far_steady_[slot] = 0;  // fading in again
    if (uses_pyramid()) far_.mark(slot);                   // its sums change at the next fill
    return;
  }
  Probe q;
  q.tag = probe.tag;
  q.position = probe.position;
  store(q, probe.sh);
  if (probe.has_lamp_layer) q.lamps = pool_.add(format_.store(probe.sh_lamps));
  q.near_lamps = !lamps_.empty() && near_lamps(probe.position);
  q.spacing = static_cast<float>(it->second.spacing);
  q.data_time = probe.requested_time;
  q.light = it->second.light;
  Sh9Rgb before;
  const bool had = interpolate(probe.position, before, nullptr, false);
  const Sh9Rgb value = current(q);
  if (adapt_ && had) {
    const double a = luminance_l00(before), b = luminance_l00(value);
    if (std::abs(a - b) > adapt_de_ * std::max({a, b, 1e-9})) q.detail = 0.5;
  }
  // The first probe anywhere has nothing to blend from but a guess: it shows its own value.
  if (had) q.from = pool_.add(before);
  // The larger the change it brings, the slower it fades in (a change spread over more
  // frames stays under the visible step per frame), up to fade_max_s.
  q.fade_in = static_cast<float>(fade_s_);
  if (fade_rate_ > 0.0 && had) {
    q.fade_in = static_cast<float>(std::clamp(log_change(before, value) / fade_rate_, fade_s_,
                                              std::max(fade_s_, fade_max_s_)));
  }
  in_flight_.erase(it);
  probes_.push_back(q);
  // Probes delivered since the last rebuild are scanned by every query: keep that tail short.
  // The far field holds every probe at once (its sums for the new one start at the next
  // update(), when its fade-in starts).
  if (probes_.size() - index_.size() > kUnindexedTail) {
    reindex();
  } else if (uses_pyramid()) {
    far_.append(q.position);
  }
}

void DemandPlanner::update(const FrameContext& ctx) {
  const double dt = ctx.time - now_;
  now_ = ctx.time;
  focus_ = make_focus(ctx, prediction_);
  // The light's change where each probe stands, integrated since its capture: its expected
  // relative error. The world reports rates (its time of day, weather and lamp schedule),
  // never the lighting at a point.
  const WorldQueries* w = ctx.world;
  const bool changing = w != nullptr && !w->lighting_static && w->lighting;
  double lamp_rate = 0.0;
  if (changing) {
    const LightingInfo info = w->lighting(now_);
    lamp_level_ = info.lamp_level;
    lamp_rate = info.lamp_change_rate;
    if (refresh_by_error_ && dt > 0.0) {
      for (auto& q : probes_) {
        if (q.fade_out_start >= 0.0) continue;
        double rate = w->lighting_change_at ? w->lighting_change_at(q.position, now_)
                                            : info.sun_sky_change_rate;
        if (q.near_lamps && !q.has_lamps()) rate += lamp_rate;
        q.drift += static_cast<float>(rate * q.sensitivity * dt);
      }
    }
    light_now_ = scene_light(info);
  }
  // A probe nearer to the camera than `inside` (squared) is nearer to the focus segment, which
  // starts there, than its limit, 1.5 max_distance, by far more than the rounding of either
  // distance: it stays without the segment distance (a division and a root per probe, most of
  // this loop's cost).
  const double limit = 1.5 * max_distance_;
  const double inside = limit * limit * (1.0 - 1e-9);
  std::size_t staying = 0;
  for (auto& q : probes_) {
    if (q.fade_in_start < 0.0) q.fade_in_start = now_;
    // Faded in (or leaving, which shows its own value): the set it faded from is not needed.
    if (q.from >= 0 && (q.fade_out_start >= 0.0 || fade_in_fraction(q) >= 1.0)) {
      pool_.release(q.from);
    }
    if (q.fade_out_start >= 0.0) continue;
    const glm::dvec3 v = q.position - focus_.now;
    const bool near = v.x * v.x + v.y * v.y + v.z * v.z < inside;
    if (now_ - q.data_time > lifetime_s_ || (!near && focus_.distance(q.position) > limit)) {
      q.fade_out_start = now_;
    } else {
      ++staying;
    }
  }
  // Over the cap: the farthest leave (fading), never the ones the camera is using; among equally
  // far ones the first in slot order. One pass and a partial sort: taking the farthest once per
  // probe over the cap rescanned every probe each time (a fifth of a frame's samples at 1e3
  // probes in BM_Frame/ambisim, where each frame's deliveries go over the cap).
  if (staying > max_probes_) {
    struct Far {
      double distance;
      std::size_t slot;
    };
    std::vector<Far> candidates;
    candidates.reserve(staying);
    for (std::size_t i = 0; i < probes_.size(); ++i) {
      if (probes_[i].fade_out_start < 0.0) {
        candidates.push_back({focus_.distance(probes_[i].position), i});
      }
    }
    const auto leaving = static_cast<std::ptrdiff_t>(staying - max_probes_);
    std::partial_sort(candidates.begin(), candidates.begin() + leaving, candidates.end(),
                      [](const Far& a, const Far& b) {
                        return a.distance != b.distance ? a.distance > b.distance : a.slot < b.slot;
                      });
    for (std::ptrdiff_t k = 0; k < leaving; ++k) {
      probes_[candidates[static_cast<std::size_t>(k)].slot].fade_out_start = now_;
    }
  }
  // Probes that have faded out weigh nothing anywhere; they are dropped from probes_ (and the
  // index rebuilt, as it addresses probes by position) once more than kUnindexedTail of them
  // wait, so that a frame in which one leaves does not pay for a rebuild.
  std::size_t dead = 0;
  for (auto& q : probes_) {
    if (!gone(q)) continue;
    pool_.release(q.from);
    pool_.release(q.lamps);
    // A gone probe weighs nothing, and stays gone (fade_out_start is set once, the clock only
    // moves on): its set is never read again.
    pool_.release(q.full);
    ++dead;
  }
  if (dead > kUnindexedTail) {
    // One pass decides who stays and moves them down; the same map then carries the receivers'
    // memos to the probes' new slots.
    std::vector<std::int32_t> new_slot(probes_.size(), -1);
    std::size_t kept = 0;
    for (std::size_t i = 0; i < probes_.size(); ++i) {
      if (gone(probes_[i])) continue;
      new_slot[i] = static_cast<std::int32_t>(kept);
      if (kept != i) probes_[kept] = std::move(probes_[i]);
      ++kept;
    }
    probes_.resize(kept);
    reindex(new_slot);
  }
  // Presences and values moved with the clock and the light: the looks and the far field's
  // sums follow.
  follow_probes(false);
}

bool DemandPlanner::gone(const Probe& q) const {
  return q.fade_out_start >= 0.0 && now_ - q.fade_out_start >= fade_s_;
}

void DemandPlanner::set_receivers(const std::vector<ReceiverView>& receivers) {
  receivers_ = receivers;
}

PlannerStats DemandPlanner::stats() const {
  PlannerStats s;
  s.live_probes = static_cast<std::int64_t>(
      std::count_if(probes_.begin(), probes_.end(), [&](const Probe& q) { return !gone(q); }));
  // What is held, as held: the probes (their sets inline as fp16 bits, or in the pool as fp32),
  // the pool of fp32, fading and lamp sets, the index, the far field and what its last fill
  // saw, the pending captures (std::map nodes:
  // about 4 pointers of overhead each), the receivers and their nearest-probe memos.
  const std::size_t per_pending = sizeof(Pending) + sizeof(std::uint64_t) + 4 * sizeof(void*);
  s.bytes = static_cast<std::int64_t>(
      probes_.size() * sizeof(Probe) + pool_.sets.size() * sizeof(Sh9Rgb) +
      pool_.free.size() * sizeof(std::int32_t) + index_.bytes() + far_.bytes() +
      far_steady_.capacity() + (planned_.size() + in_flight_.size()) * per_pending +
      receivers_.size() * sizeof(ReceiverView) + nearest_memo_.capacity() * sizeof(NearestMemo));
  return s;
}

void DemandPlanner::describe_nodes(std::vector<ProbeNodeView>& out) const {
  for (const auto& q : probes_) {
    if (gone(q)) continue;
    ProbeNodeView v;
    v.centre = q.position;
    v.half_extent = glm::dvec3(0.5 * static_cast<double>(q.spacing * q.detail));
    v.depth = q.detail < 1.0 ? 1 : 0;
    v.has_data = true;
    v.age_s = now_ - q.data_time;
    v.sh = stored(q);
    out.push_back(v);
  }
  for (const auto& [tag, f] : in_flight_) {
    ProbeNodeView v;
    v.centre = f.position;
    v.half_extent = glm::dvec3(0.5 * f.spacing);
    v.in_flight = true;
    out.push_back(v);
  }
}

}  // namespace ambisim
