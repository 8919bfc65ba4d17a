#include "policies/baselines/oracle.h"

#include <limits>

#include <glm/geometric.hpp>

#include "policies/core/default_ambient.h"

namespace ambisim {

PlannerInfo OraclePlanner::info() {
  return {"oracle",
          "captures at every receiver every frame without budget: the representation's ceiling",
          {},
          [](const PlannerParams& p) { return std::make_unique<OraclePlanner>(p); }};
}

OraclePlanner::OraclePlanner(const PlannerParams& params) : params_(params) {}

void OraclePlanner::set_receivers(const std::vector<ReceiverView>& receivers) {
  receivers_ = receivers;
}

std::vector<CaptureRequest> OraclePlanner::plan(const FrameContext& ctx) {
  plan_frame_ = ctx.frame;
  std::vector<CaptureRequest> out;
  out.reserve(receivers_.size());
  for (const auto& r : receivers_) out.push_back({r.position, next_tag_++});
  return out;
}

void OraclePlanner::started(std::uint64_t /*tag*/) { ++in_flight_; }

void OraclePlanner::update(const FrameContext& /*ctx*/) {}

void OraclePlanner::deliver(const FinishedProbe& probe) {
  // The first delivery of a new frame replaces the previous batch. Clearing here rather than in
  // plan() keeps the last batch usable if a simulator ever delivers after the lookups.
  if (batch_frame_ != plan_frame_) {
    probes_.clear();
    by_position_.clear();
    batch_frame_ = plan_frame_;
  }
  if (in_flight_ > 0) --in_flight_;
  by_position_.emplace(key_of(probe.position), probes_.size());
  probes_.push_back(probe);
}

LookupResult OraclePlanner::lookup(const glm::dvec3& p) const {
  LookupResult r;
  const FinishedProbe* best = nullptr;
  double best_d = std::numeric_limits<double>::infinity();
  if (auto it = by_position_.find(key_of(p)); it != by_position_.end()) {
    best = &probes_[it->second];
    best_d = 0.0;
  } else {
    for (const auto& q : probes_) {  // ties: the earliest delivered
      const double d = glm::distance(q.position, p);
      if (d < best_d) {
        best_d = d;
        best = &q;
      }
    }
  }
  if (!best) return default_ambient_lookup();
  r.sh = best->sh;
  r.contributors[0] = {best->tag, 1.0f};
  r.contributor_count = 1;
  r.spacing_m = best_d;
  r.data_time = best->requested_time;
  return r;
}

PlannerStats OraclePlanner::stats() const {
  PlannerStats s;
  s.live_probes = static_cast<std::int64_t>(probes_.size());
  s.bytes = static_cast<std::int64_t>(probes_.size() * sizeof(FinishedProbe) +
                                      by_position_.size() * (sizeof(Key) + sizeof(std::size_t)) +
                                      receivers_.size() * sizeof(ReceiverView));
  return s;
}

}  // namespace ambisim
