#pragma once
// `oracle`: the accuracy ceiling of the representation. Each frame it asks for a capture at
// every receiver; ignores_budget() makes the simulator start all of them, render all six faces
// at once and deliver them before the frame's lookups. A lookup returns the newest frame's
// probe nearest the point: exactly the receiver's own probe at a receiver position.
#include <array>
#include <cstdint>
#include <map>
#include <vector>

#include "policies/core/planner_info.h"
#include "policies/core/planner_params.h"
#include "sim/planner.h"

namespace ambisim {

class OraclePlanner final : public Planner {
 public:
  static PlannerInfo info();
  explicit OraclePlanner(const PlannerParams& params);

  std::string name() const override { return "oracle"; }
  nlohmann::json params() const override { return params_.to_json(); }

  std::vector<CaptureRequest> plan(const FrameContext& ctx) override;
  void started(std::uint64_t tag) override;
  void deliver(const FinishedProbe& probe) override;
  void update(const FrameContext& ctx) override;
  // Nearest probe of the newest delivered batch; spacing_m = its distance (0 at a receiver).
  // Before any delivery: black, fell_back.
  LookupResult lookup(const glm::dvec3& p) const override;
  PlannerStats stats() const override;

  void set_receivers(const std::vector<ReceiverView>& receivers) override;
  bool ignores_budget() const override { return true; }

 private:
  using Key = std::array<double, 3>;  // exact position, for O(log n) receiver hits
  static Key key_of(const glm::dvec3& p) { return {p.x, p.y, p.z}; }

  PlannerParams params_;
  std::vector<ReceiverView> receivers_;
  std::uint64_t next_tag_ = 1;
  std::int64_t plan_frame_ = -1;   // frame of the latest plan()
  std::int64_t batch_frame_ = -1;  // frame whose probes are stored
  std::vector<FinishedProbe> probes_;
  std::map<Key, std::size_t> by_position_;  // first probe at each exact position
  std::int64_t in_flight_ = 0;
};

}  // namespace ambisim
