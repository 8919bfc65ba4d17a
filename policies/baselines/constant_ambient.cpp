#include "policies/baselines/constant_ambient.h"

#include <limits>
#include <numbers>

#include "policies/core/default_ambient.h"

namespace ambisim {
namespace {

std::vector<ParamSpec> rgb_params(const std::string& prefix, double grey, const std::string& what) {
  std::vector<ParamSpec> out;
  for (const char* ch : {"r", "g", "b"}) {
    out.push_back(number_param(
        prefix + "_" + ch, grey, Range::non_negative(),
        std::string("linear ") + ch + " radiance of " + what + " before the capture arrives"));
  }
  return out;
}

Rgb read_rgb(const PlannerParams& p, const std::string& prefix) {
  return Rgb(static_cast<float>(p.number(prefix + "_r")),
             static_cast<float>(p.number(prefix + "_g")),
             static_cast<float>(p.number(prefix + "_b")));
}

}  // namespace

PlannerInfo ConstantAmbientPlanner::constant_info() {
  return {"constant",
          "classic constant ambient (thesis 10.1.1): the L00 term of one capture at the start",
          rgb_params("colour", 0.5, "the default uniform ambient"), [](const PlannerParams& p) {
            return std::make_unique<ConstantAmbientPlanner>(Mode::constant, p);
          }};
}

PlannerInfo ConstantAmbientPlanner::hemisphere_info() {
  std::vector<ParamSpec> specs =
      rgb_params("sky", kDefaultSkyRadiance, "the default upper hemisphere");
  for (auto& s : rgb_params("ground", kDefaultGroundRadiance, "the default lower hemisphere"))
    specs.push_back(s);
  return {"hemisphere", "hemisphere ambient (thesis 10.1.2): L00 + L10 of one capture at the start",
          specs, [](const PlannerParams& p) {
            return std::make_unique<ConstantAmbientPlanner>(Mode::hemisphere, p);
          }};
}

ConstantAmbientPlanner::ConstantAmbientPlanner(Mode mode, const PlannerParams& params)
    : mode_(mode), params_(params) {
  // Projections of the default radiance: uniform L gives L00 = sqrt(4 pi) L; sky A above and
  // ground B below give L00 = sqrt(pi) (A + B), L10 = pi Y1 (A - B) and nothing else up to l=2.
  const double y0 = kShY00 * 4.0 * std::numbers::pi;
  if (mode_ == Mode::constant) {
    fallback_.c[0] = read_rgb(params_, "colour") * static_cast<float>(y0);
  } else {
    fallback_ = hemisphere_sh(read_rgb(params_, "sky"), read_rgb(params_, "ground"));
  }
}

std::string ConstantAmbientPlanner::name() const {
  return mode_ == Mode::constant ? "constant" : "hemisphere";
}

Sh9Rgb ConstantAmbientPlanner::keep(Mode mode, const Sh9Rgb& sh) {
  Sh9Rgb r;
  r.c[0] = sh.c[0];
  if (mode == Mode::hemisphere) r.c[2] = sh.c[2];  // L10: the vertical (z up) band-1 term
  return r;
}

std::vector<CaptureRequest> ConstantAmbientPlanner::preload(const FrameContext& ctx) {
  requested_ = true;
  return {{ctx.camera_position, tag_}};
}

std::vector<CaptureRequest> ConstantAmbientPlanner::plan(const FrameContext& ctx) {
  if (held_ || requested_ || ctx.startable_captures <= 0) return {};
  requested_ = true;  // cleared again if refused
  return {{ctx.camera_position, tag_}};
}

void ConstantAmbientPlanner::started(std::uint64_t /*tag*/) {}

void ConstantAmbientPlanner::refused(std::uint64_t tag) {
  if (tag == tag_) {
    requested_ = false;
    ++tag_;  // a fresh tag for the retry
  }
}

void ConstantAmbientPlanner::deliver(const FinishedProbe& probe) {
  if (held_) return;  // only the first capture counts
  held_ = Held{probe.tag, keep(mode_, probe.sh), probe.requested_time};
}

void ConstantAmbientPlanner::update(const FrameContext& /*ctx*/) {}

LookupResult ConstantAmbientPlanner::lookup(const glm::dvec3& /*p*/) const {
  LookupResult r;
  r.fell_back = true;
  r.spacing_m = std::numeric_limits<double>::infinity();
  if (!held_) {
    r.sh = fallback_;
    return r;
  }
  r.sh = held_->sh;
  r.contributors[0] = {held_->tag, 1.0f};
  r.contributor_count = 1;
  r.data_time = held_->data_time;
  return r;
}

PlannerStats ConstantAmbientPlanner::stats() const {
  PlannerStats s;
  s.live_probes = held_ ? 1 : 0;
  // The held set plus the fallback set (both stored as full Sh9Rgb) and the bookkeeping.
  s.bytes = static_cast<std::int64_t>(sizeof(Sh9Rgb) + sizeof(std::optional<Held>) + sizeof(tag_) +
                                      sizeof(requested_));
  return s;
}

}  // namespace ambisim
