#pragma once
// `per_object`: the alternative the thesis rejected (7.5.1): one capture per receiver (object),
// taken at the object, re-captured when the object has moved more than move_m from where its
// capture was taken (the thesis' "every 5 m") or the capture is older than lifetime_s.
// Priority: objects without any capture first (oldest spawned, i.e. lowest id, first), then
// the most outdated, max(moved / move_m, age / lifetime_s). plan() asks for at most
// ctx.startable_captures captures, so what cannot start waits in the backlog (backlog()).
// Objects that despawn (absent from set_receivers) are forgotten with their capture; a capture
// of a forgotten object that is still being rendered is dropped on delivery.
//
// Lookup(p): the capture of the receiver nearest p among those holding one (a receiver looked
// up at its own position gets its own capture, if it has one; otherwise, like a demand point,
// its nearest captured neighbour's). spacing_m = distance from p to where that capture was
// taken, so a capture the object has driven away from is reported as the gap it is. No
// capture anywhere: black, fell_back, spacing_m = inf.
#include <array>
#include <cstdint>
#include <map>
#include <vector>

#include "policies/core/coefficient_format.h"
#include "policies/core/planner_info.h"
#include "policies/core/planner_params.h"
#include "sim/planner.h"

namespace ambisim {

class PerObjectPlanner final : public Planner {
 public:
  static PlannerInfo info();
  explicit PerObjectPlanner(const PlannerParams& params);

  std::string name() const override { return "per_object"; }
  nlohmann::json params() const override { return params_.to_json(); }

  std::vector<CaptureRequest> plan(const FrameContext& ctx) override;
  void started(std::uint64_t tag) override;
  void refused(std::uint64_t tag) override;
  void deliver(const FinishedProbe& probe) override;
  void update(const FrameContext& ctx) override;
  LookupResult lookup(const glm::dvec3& p) const override;
  PlannerStats stats() const override;
  void set_receivers(const std::vector<ReceiverView>& receivers) override;
  void describe_nodes(std::vector<ProbeNodeView>& out) const override;

  // Receivers that need a capture (none yet, moved, or too old) and have none in flight.
  std::size_t backlog() const;
  std::size_t tracked() const { return objects_.size(); }

 private:
  struct Object {
    glm::dvec3 position{0.0};  // at the latest set_receivers()
    bool has_capture = false;
    bool in_flight = false;
    glm::dvec3 capture_position{0.0};
    Sh9Rgb sh;               // as stored
    double data_time = 0.0;  // request time of the capture (D6)
    std::uint64_t tag = 0;
  };
  using Key = std::array<double, 3>;  // exact position, for O(log n) receiver hits

  bool needs_capture(const Object& o) const;
  // How overdue a captured object is: > 1 means due.
  double outdatedness(const Object& o) const;

  PlannerParams params_;
  CoefficientFormat format_;
  double move_m_;
  double lifetime_s_;

  double now_ = 0.0;
  std::uint64_t next_tag_ = 1;
  std::map<std::uint64_t, Object> objects_;   // by receiver id (spawn order)
  std::map<Key, std::uint64_t> by_position_;  // receiver position -> id (first id wins)
  // The receivers of the last set_receivers(), to skip the rebuild when none changed.
  struct Placed {
    std::uint64_t id;
    glm::dvec3 position;
  };
  std::vector<Placed> last_receivers_;
  // by_position_'s nodes between two set_receivers() passes (empty otherwise).
  std::vector<std::map<Key, std::uint64_t>::node_type> spare_positions_;
  std::map<std::uint64_t, std::uint64_t> pending_;    // tag -> receiver id, not yet started
  std::map<std::uint64_t, std::uint64_t> in_flight_;  // tag -> receiver id, being rendered
};

}  // namespace ambisim
