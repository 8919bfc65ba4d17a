#pragma once
// `shgraph`, `shgraph+vp`, `shgraph+route`: the thesis' SHGraph (8.4.2, Bilaga B) in 3D. The
// machinery is ShGraphCore<3> (policies/thesis/shgraph_core.h); the variants differ only in the
// prediction defaults: none, straight-line velocity prediction (D15), along the road.
#include <string>

#include "policies/core/planner_info.h"
#include "policies/core/planner_params.h"
#include "policies/thesis/shgraph_core.h"
#include "sim/planner.h"

namespace ambisim {

class ShGraphPlanner final : public Planner {
 public:
  static PlannerInfo info();        // shgraph
  static PlannerInfo info_vp();     // shgraph+vp
  static PlannerInfo info_route();  // shgraph+route
  ShGraphPlanner(std::string name, const PlannerParams& params);

  std::string name() const override { return name_; }
  nlohmann::json params() const override { return params_.to_json(); }

  std::vector<CaptureRequest> plan(const FrameContext& ctx) override { return core_.plan(ctx); }
  void started(std::uint64_t tag) override { core_.started(tag); }
  void refused(std::uint64_t tag) override { core_.refused(tag); }
  void deliver(const FinishedProbe& probe) override { core_.deliver(probe); }
  void update(const FrameContext& ctx) override { core_.update(ctx); }
  LookupResult lookup(const glm::dvec3& p) const override { return core_.lookup(p); }
  PlannerStats stats() const override { return core_.stats(); }
  void describe_nodes(std::vector<ProbeNodeView>& out) const override { core_.describe_nodes(out); }

  const ShGraphCore<3>& graph() const { return core_; }
  // The reference paths of ShGraphCore::set_naive (tests, bench/).
  void set_naive(bool naive) { core_.set_naive(naive); }

 private:
  std::string name_;
  PlannerParams params_;
  ShGraphCore<3> core_;
};

}  // namespace ambisim
