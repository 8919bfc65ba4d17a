#include "policies/baselines/baked.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include <Eigen/Core>
#include <glm/geometric.hpp>

#include "policies/core/default_ambient.h"

namespace ambisim {
namespace {

std::vector<ParamSpec> lattice_params() {
  const BakedLatticeSettings d;
  return {
      number_param("spacing_m", d.spacing_m, Range::positive(),
                   "the finest level's probe spacing, within band_m of the surface"),
      integer_param("levels", d.levels, Range::closed(1, 6),
                    "levels, each 3x the spacing of the one below (APV's 1/3/9/27 m bricks)"),
      number_param("corridor_m", d.corridor_m, Range::non_negative(),
                   "half-width of the baked corridor around the level's route"),
      number_param("band_m", d.band_m, Range::positive(),
                   "height above the surface of the finest level (x3 per coarser level)"),
      number_param("top_m", d.top_m, Range::positive(),
                   "height above the surface that the coarsest level reaches"),
      number_param("clearance_m", d.clearance_m, Range::non_negative(),
                   "a probe closer to the surface is moved out (at most half a cell) or dropped"),
      integer_param("max_captures", 1000000, Range::closed(1, 1e9),
                    "the bake's budget: the finest levels are left out until it fits"),
      integer_param("bake_face_size", 24, Range::closed(4, 128),
                    "cube-face resolution of the bake (offline, not the run's budget; 24 is the "
                    "shipped reference's)"),
  };
}

BakedLatticeSettings lattice_settings(const PlannerParams& p) {
  BakedLatticeSettings s;
  s.spacing_m = p.number("spacing_m");
  s.levels = static_cast<int>(p.integer("levels"));
  s.corridor_m = p.number("corridor_m");
  s.band_m = p.number("band_m");
  s.top_m = p.number("top_m");
  s.clearance_m = p.number("clearance_m");
  return s;
}

}  // namespace

// ---- PackedSets ----

void BakedPlanner::PackedSets::reset(CoefficientFormat format, std::size_t sets) {
  format_ = format;
  stride_ = static_cast<std::size_t>(format.coefficients()) * 3;
  full_.clear();
  half_.clear();
  if (format.half) {
    half_.assign(sets * stride_, 0);
    half_.shrink_to_fit();
  } else {
    full_.assign(sets * stride_, 0.0f);
    full_.shrink_to_fit();
  }
}

void BakedPlanner::PackedSets::set(std::size_t i, const Sh9Rgb& sh) {
  const Sh9Rgb stored = format_.store(sh);
  for (int c = 0; c < format_.coefficients(); ++c) {
    for (int ch = 0; ch < 3; ++ch) {
      const std::size_t at = i * stride_ + static_cast<std::size_t>(3 * c + ch);
      if (format_.half) {
        half_[at] = std::bit_cast<std::uint16_t>(Eigen::half(stored.c[c][ch]));
      } else {
        full_[at] = stored.c[c][ch];
      }
    }
  }
}

void BakedPlanner::PackedSets::add(std::size_t i, float w, Sh9Rgb& out) const {
  for (int c = 0; c < format_.coefficients(); ++c) {
    for (int ch = 0; ch < 3; ++ch) {
      const std::size_t at = i * stride_ + static_cast<std::size_t>(3 * c + ch);
      const float v =
          format_.half ? static_cast<float>(std::bit_cast<Eigen::half>(half_[at])) : full_[at];
      out.c[c][ch] += w * v;
    }
  }
}

Sh9Rgb BakedPlanner::PackedSets::get(std::size_t i) const {
  Sh9Rgb out;
  add(i, 1.0f, out);
  return out;
}

std::int64_t BakedPlanner::PackedSets::bytes() const {
  return static_cast<std::int64_t>(full_.capacity() * sizeof(float) +
                                   half_.capacity() * sizeof(std::uint16_t));
}

// ---- BakedPlanner ----

PlannerInfo BakedPlanner::baked_info() {
  std::vector<ParamSpec> params = lattice_params();
  for (auto& s : coefficient_format_params("fp16")) params.push_back(std::move(s));
  return {"baked",
          "baked probe lattice around the route (Unity APV / Unreal volumetric lightmaps): "
          "captured before the run, never updated",
          std::move(params),
          [](const PlannerParams& p) { return std::make_unique<BakedPlanner>(Mode::baked, p); }};
}

PlannerInfo BakedPlanner::tod_info() {
  std::vector<ParamSpec> params = lattice_params();
  params.push_back(integer_param("times", 8, Range::closed(1, 64),
                                 "lighting states baked, evenly over the run (AC4: 8)"));
  for (auto& s : coefficient_format_params("fp16")) params.push_back(std::move(s));
  return {"baked_tod",
          "the baked lattice at K times of day, blended linearly by the current time "
          "(Assassin's Creed IV)",
          std::move(params), [](const PlannerParams& p) {
            return std::make_unique<BakedPlanner>(Mode::time_of_day, p);
          }};
}

BakedPlanner::BakedPlanner(Mode mode, const PlannerParams& params)
    : mode_(mode),
      params_(params),
      format_(coefficient_format_from(params)),
      settings_(lattice_settings(params)),
      bake_count_(mode == Mode::time_of_day ? static_cast<std::size_t>(params.integer("times"))
                                            : 1) {}

std::string BakedPlanner::name() const { return mode_ == Mode::baked ? "baked" : "baked_tod"; }

std::vector<CaptureRequest> BakedPlanner::preload(const FrameContext& ctx) {
  now_ = ctx.time;
  camera_ = ctx.camera_position;
  const WorldQueries* world = ctx.world;
  std::vector<glm::dvec3> route;
  if (world != nullptr) route = world->route;
  if (route.empty()) route.push_back(ctx.camera_position);
  BakedLattice::Surface surface = [](double, double) { return 0.0; };
  if (world != nullptr && world->surface_height) surface = world->surface_height;

  // The bake times: K evenly over the run; with one, or a run of unknown length, frame 0's.
  const std::size_t wanted = mode_ == Mode::time_of_day
                                 ? static_cast<std::size_t>(params_.integer("times"))
                                 : std::size_t{1};
  const double span = ctx.run_duration_s;
  bake_count_ = wanted > 1 && span > 0.0 ? wanted : 1;
  times_.assign(bake_count_, ctx.time);
  for (std::size_t k = 1; k < bake_count_; ++k) {
    times_[k] = span * static_cast<double>(k) / static_cast<double>(bake_count_ - 1);
  }
  BakedLatticeSettings settings = settings_;
  settings.max_points =
      static_cast<double>(params_.integer("max_captures")) / static_cast<double>(bake_count_);
  lattice_ = world != nullptr
                 ? BakedLattice(route, surface, settings, world->object_cells, world->object_cell_m)
                 : BakedLattice(route, surface, settings);

  const std::size_t n = lattice_.size();
  sets_.reset(format_, n * bake_count_);
  present_.assign(n * bake_count_, 0);
  present_.shrink_to_fit();
  live_sets_ = 0;
  std::vector<CaptureRequest> out;
  out.reserve(n * bake_count_);
  // In time order (the simulator renders them so anyway), probes in lattice order.
  for (std::size_t k = 0; k < bake_count_; ++k) {
    for (std::size_t i = 0; i < n; ++i) {
      CaptureRequest r;
      r.position = lattice_.position(i);
      r.tag = static_cast<std::uint64_t>(i * bake_count_ + k + 1);
      r.time = bake_count_ > 1 ? times_[k] : -1.0;
      r.face_size = static_cast<int>(params_.integer("bake_face_size"));
      out.push_back(r);
    }
  }
  return out;
}

std::vector<CaptureRequest> BakedPlanner::plan(const FrameContext& ctx) {
  now_ = ctx.time;
  camera_ = ctx.camera_position;
  return {};  // baked: nothing is ever captured at run time
}

void BakedPlanner::deliver(const FinishedProbe& probe) {
  if (probe.tag == 0 || probe.tag > present_.size()) return;
  const std::size_t set = static_cast<std::size_t>(probe.tag - 1);
  sets_.set(set, probe.sh);
  if (present_[set] == 0) ++live_sets_;
  present_[set] = 1;
}

void BakedPlanner::update(const FrameContext& ctx) {
  now_ = ctx.time;
  camera_ = ctx.camera_position;
}

void BakedPlanner::bracket(double time, std::size_t* k0, std::size_t* k1, float* w) const {
  if (times_.size() <= 1) {
    *k0 = *k1 = 0;
    *w = 0.0f;
    return;
  }
  const auto it = std::upper_bound(times_.begin(), times_.end(), time);
  const std::size_t hi = std::clamp<std::size_t>(static_cast<std::size_t>(it - times_.begin()),
                                                 std::size_t{1}, times_.size() - 1);
  *k0 = hi - 1;
  *k1 = hi;
  const double t0 = times_[*k0], t1 = times_[*k1];
  *w = static_cast<float>(t1 > t0 ? std::clamp((time - t0) / (t1 - t0), 0.0, 1.0) : 0.0);
}

Sh9Rgb BakedPlanner::stored(std::size_t probe, std::size_t k) const {
  return sets_.get(probe * bake_count_ + k);
}

LookupResult BakedPlanner::lookup(const glm::dvec3& p) const {
  if (lattice_.size() == 0) return default_ambient_lookup();
  std::size_t k0 = 0, k1 = 0;
  float w = 0.0f;
  bracket(now_, &k0, &k1, &w);
  const std::size_t K = bake_count_;
  // One reference captured: small enough for std::function's inline storage (no allocation).
  const struct {
    const std::uint8_t* present;
    std::size_t K, k0, k1;
  } sets{present_.data(), K, k0, k1};
  const BakedLattice::Cell cell = lattice_.find(p, [&sets](std::uint32_t i) {
    return sets.present[i * sets.K + sets.k0] != 0 && sets.present[i * sets.K + sets.k1] != 0;
  });
  if (cell.level < 0) return default_ambient_lookup();
  LookupResult r;
  r.sh = Sh9Rgb{};
  const std::size_t nearest = w < 0.5f ? k0 : k1;
  for (int m = 0; m < cell.count; ++m) {
    const std::size_t i = cell.probe[static_cast<std::size_t>(m)];
    const float wi = static_cast<float>(cell.weight[static_cast<std::size_t>(m)]);
    if (k1 == k0) {
      sets_.add(i * K + k0, wi, r.sh);
    } else {
      sets_.add(i * K + k0, wi * (1.0f - w), r.sh);
      sets_.add(i * K + k1, wi * w, r.sh);
    }
    r.contributors[static_cast<std::size_t>(m)] = {static_cast<std::uint64_t>(i * K + nearest + 1),
                                                   wi};
  }
  r.contributor_count = cell.count;
  r.fell_back = false;
  r.spacing_m = lattice_.spacing(cell.level);
  r.data_time = times_.empty() ? 0.0 : times_[k0] + w * (times_[k1] - times_[k0]);
  return r;
}

PlannerStats BakedPlanner::stats() const {
  PlannerStats s;
  s.live_probes = live_sets_;
  s.nodes = static_cast<std::int64_t>(lattice_.size());
  s.bytes = sets_.bytes() + static_cast<std::int64_t>(present_.capacity()) +
            static_cast<std::int64_t>(times_.capacity() * sizeof(double)) + lattice_.bytes();
  return s;
}

void BakedPlanner::describe_nodes(std::vector<ProbeNodeView>& out) const {
  std::size_t k0 = 0, k1 = 0;
  float w = 0.0f;
  bracket(now_, &k0, &k1, &w);
  const std::size_t K = bake_count_;
  for (std::size_t i = 0; i < lattice_.size(); ++i) {
    if (glm::distance(lattice_.position(i), camera_) > kViewRadius_m) continue;
    ProbeNodeView v;
    v.centre = lattice_.position(i);
    v.depth = lattice_.probe(i).level;
    v.has_data = present_[i * K + k0] != 0 && present_[i * K + k1] != 0;
    if (v.has_data) {
      sets_.add(i * K + k0, 1.0f - w, v.sh);
      if (k1 != k0) sets_.add(i * K + k1, w, v.sh);
      v.age_s = now_ - (times_[k0] + w * (times_[k1] - times_[k0]));
    }
    out.push_back(v);
  }
}

}  // namespace ambisim
