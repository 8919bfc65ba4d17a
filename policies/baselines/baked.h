#pragma once
// The baked baselines: what a team ships instead of capturing at run time (SPEC 7).
// - `baked` (Unity APV / Unreal volumetric lightmaps): a dense lattice of probes around the
//   level's whole route and every square its lit objects visit (WorldQueries::object_cells:
//   the traffic's lanes far ahead of the camera; baked_lattice.h: finest near the surface, 3x
//   coarser per level above it, probes inside the terrain moved out or dropped), every probe
//   captured before the first frame (preload, no budget: the bake) in frame 0's light at
//   bake_face_size (offline quality, not the run's budget), and never updated.
//   plan() never asks for anything.
// - `baked_tod` (Assassin's Creed IV: probes baked at K times of day, blended by the current
//   time): the same lattice captured at K lighting states t_k = k T / (K - 1), k = 0 .. K - 1,
//   spread over the run's length T (FrameContext::run_duration_s; K = 1 or T = 0: frame 0's
//   light only); a lookup at time t blends the two bake times around t linearly,
//   (1 - w) S_k + w S_k+1 with w = (t - t_k) / (t_k+1 - t_k), clamped to [t_0, t_K-1].
// Lookup: trilinear in the finest level's cell around the point with data (weights
// renormalised over the usable corners), falling back to coarser levels, then to the default
// ambient (policies/core/default_ambient.h). spacing_m = the level's spacing; contributors =
// the corners (tag of the corner's set nearest the time for baked_tod); data_time = the bake
// time the data shows (0 for baked; the blended bake time for baked_tod).
// Memory (stats().bytes): the coefficient sets as stored (packed fp32 or fp16, 4 or 9
// coefficients per channel), one presence byte per set, and the lattice itself.
#include <cstdint>
#include <vector>

#include "policies/baselines/baked_lattice.h"
#include "policies/core/coefficient_format.h"
#include "policies/core/planner_info.h"
#include "policies/core/planner_params.h"
#include "sim/planner.h"

namespace ambisim {

class BakedPlanner final : public Planner {
 public:
  enum class Mode { baked, time_of_day };

  static PlannerInfo baked_info();
  static PlannerInfo tod_info();
  BakedPlanner(Mode mode, const PlannerParams& params);

  std::string name() const override;
  nlohmann::json params() const override { return params_.to_json(); }

  // Builds the lattice around ctx.world->route (the camera's position without one) and asks
  // for every probe at every bake time.
  std::vector<CaptureRequest> preload(const FrameContext& ctx) override;
  std::vector<CaptureRequest> plan(const FrameContext& ctx) override;
  void started(std::uint64_t /*tag*/) override {}
  void deliver(const FinishedProbe& probe) override;
  void update(const FrameContext& ctx) override;
  LookupResult lookup(const glm::dvec3& p) const override;
  PlannerStats stats() const override;
  // The probes within kViewRadius_m of the camera: a level's bake holds tens of thousands, and
  // every snapshot of the views would carry them all (on the motorway 25 m gave 1,350 nodes a
  // snapshot, 45 MB of views; 15 m gives 22 MB).
  void describe_nodes(std::vector<ProbeNodeView>& out) const override;

  static constexpr double kViewRadius_m = 15.0;
  const BakedLattice& lattice() const { return lattice_; }
  const std::vector<double>& bake_times() const { return times_; }
  // The bake time k's set of probe i (for tests).
  Sh9Rgb stored(std::size_t probe, std::size_t k) const;

 private:
  // The coefficient sets, packed as stored: coefficients() x 3 values per set, fp32 or fp16.
  class PackedSets {
   public:
    void reset(CoefficientFormat format, std::size_t sets);
    void set(std::size_t i, const Sh9Rgb& sh);
    Sh9Rgb get(std::size_t i) const;
    // Adds w x set i to out (only the stored coefficients).
    void add(std::size_t i, float w, Sh9Rgb& out) const;
    std::int64_t bytes() const;

   private:
    CoefficientFormat format_;
    std::size_t stride_ = 0;
    std::vector<float> full_;
    std::vector<std::uint16_t> half_;  // fp16 bit patterns
  };

  // The two bake times blended at `time`, and the later one's weight.
  void bracket(double time, std::size_t* k0, std::size_t* k1, float* w) const;

  Mode mode_;
  PlannerParams params_;
  CoefficientFormat format_;
  BakedLatticeSettings settings_;
  std::size_t bake_count_ = 1;  // K
  std::vector<double> times_;   // the bake times, ascending
  BakedLattice lattice_;
  PackedSets sets_;                    // probe i, bake k: set i x K + k (tag = that + 1)
  std::vector<std::uint8_t> present_;  // per set: delivered
  std::int64_t live_sets_ = 0;
  double now_ = 0.0;
  glm::dvec3 camera_{0.0};
};

}  // namespace ambisim
