#pragma once
// `shgraph2d`: the ground sheet the thesis' engine ended with (7.5.3 L308, 8.5 L596, 9.3,
// D12): sets only on a sheet height_m above the terrain, a 3x3 (9-child) hierarchy over the
// horizontal axes with 4 neighbour links, the D2 rule with k = 3, and a lookup of the nearest
// set per quadrant (1-4) interpolated by horizontal distance. Same machinery as `shgraph`
// (ShGraphCore<2>). Prediction is on by default: the engine version planned ahead with the
// game's knowledge of motion (L584, L588).
#include <string>

#include "policies/core/planner_info.h"
#include "policies/core/planner_params.h"
#include "policies/thesis/shgraph_core.h"
#include "sim/planner.h"

namespace ambisim {

class ShGraph2dPlanner final : public Planner {
 public:
  static PlannerInfo info();
  explicit ShGraph2dPlanner(const PlannerParams& params);

  std::string name() const override { return "shgraph2d"; }
  nlohmann::json params() const override { return params_.to_json(); }

  std::vector<CaptureRequest> plan(const FrameContext& ctx) override { return core_.plan(ctx); }
  void started(std::uint64_t tag) override { core_.started(tag); }
  void refused(std::uint64_t tag) override { core_.refused(tag); }
  void deliver(const FinishedProbe& probe) override { core_.deliver(probe); }
  void update(const FrameContext& ctx) override { core_.update(ctx); }
  LookupResult lookup(const glm::dvec3& p) const override { return core_.lookup(p); }
  PlannerStats stats() const override { return core_.stats(); }
  void describe_nodes(std::vector<ProbeNodeView>& out) const override { core_.describe_nodes(out); }

  const ShGraphCore<2>& graph() const { return core_; }
  // The reference paths of ShGraphCore::set_naive (tests, bench/).
  void set_naive(bool naive) { core_.set_naive(naive); }

 private:
  PlannerParams params_;
  ShGraphCore<2> core_;
};

}  // namespace ambisim
