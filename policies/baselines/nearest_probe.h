#pragma once
// `nearest`: the Half-Life 2 style baseline (RTR 9.9.3) with time averaging. It requests a
// capture at the camera (optionally at the camera predicted one capture latency ahead)
// whenever no finished or in-flight probe lies within spacing_m of that point, at most one
// request per frame. A lookup returns the nearest finished probe. A newly delivered probe
// fades in over blend_s from the value lookups had at its position just before it arrived
// (the previous nearest probe there, itself possibly mid-fade), so a new probe does not pop.
// Retention: probes older than lifetime_s (from their request time, D6) are dropped, and beyond
// max_probes the probe farthest from the camera goes first. Before any probe exists lookups
// return black with fell_back = true (an honest "no data", which the error metrics then see).
#include <cstdint>
#include <map>
#include <optional>
#include <vector>

#include "policies/core/planner_info.h"
#include "policies/core/planner_params.h"
#include "sim/planner.h"

namespace ambisim {

class NearestProbePlanner final : public Planner {
 public:
  static PlannerInfo info();
  explicit NearestProbePlanner(const PlannerParams& params);

  std::string name() const override { return "nearest"; }
  nlohmann::json params() const override { return params_.to_json(); }

  std::vector<CaptureRequest> plan(const FrameContext& ctx) override;
  void started(std::uint64_t tag) override;
  void refused(std::uint64_t tag) override;
  void deliver(const FinishedProbe& probe) override;
  void update(const FrameContext& ctx) override;
  // spacing_m = distance to the probe used; contributors: the probe (and, mid-fade, the probe
  // it fades from, weighted 1 - t).
  LookupResult lookup(const glm::dvec3& p) const override;
  PlannerStats stats() const override;
  void describe_nodes(std::vector<ProbeNodeView>& out) const override;

 private:
  struct Probe {
    std::uint64_t tag = 0;
    glm::dvec3 position{0.0};
    Sh9Rgb sh;
    double data_time = 0.0;  // request time (D6)
    // Fade-in: from `from` (the lookup value here at delivery) over blend_s, starting at the
    // first update() after delivery, when the probe becomes usable.
    bool fading = false;
    bool fade_start_known = false;
    double fade_start = 0.0;
    Sh9Rgb from;
    std::uint64_t from_tag = 0;  // 0: `from` came from no probe
    double from_data_time = 0.0;
  };
  struct InFlight {
    glm::dvec3 position{0.0};
    double requested_time = 0.0;
  };

  // Index of the nearest probe to p (ties: the older tag), or none.
  std::optional<std::size_t> nearest(const glm::dvec3& p, double* distance) const;
  float fade_weight(const Probe& q) const;
  void enforce_cap();

  PlannerParams params_;
  double spacing_m_;
  std::size_t max_probes_;
  double lifetime_s_;
  double blend_s_;
  bool predict_;

  double now_ = 0.0;
  glm::dvec3 camera_{0.0};
  std::uint64_t next_tag_ = 1;
  std::vector<Probe> probes_;                    // in delivery order
  std::map<std::uint64_t, InFlight> pending_;    // returned by plan(), not yet started
  std::map<std::uint64_t, InFlight> in_flight_;  // started, not yet delivered
};

}  // namespace ambisim
