#pragma once
// The single-colour baselines of thesis 10.1 (L711-734), made fair: one capture at the camera
// at the start, taken at load time (preload: before the first frame, as a game sets its
// ambient before showing anything), then a truncated copy of it everywhere, forever.
// - `constant` (10.1.1): keeps L00 only, the DC average of all incoming light.
// - `hemisphere` (10.1.2): keeps L00 and the vertical L10 term: a sky colour above and a
//   ground colour below, interpolated by the normal's height (lerp(ground, sky, (1 + n.z)/2)
//   is exactly what L00 + L10 irradiance gives).
// Without the capture (a planner used outside the simulator) both return an artist colour from
// their parameters (a uniform radiance for constant, sky above / ground below for hemisphere).
// Coverage: every lookup reports fell_back = true and spacing_m = infinity, also after the
// capture arrived: one set for the whole world has no spatial structure, so it serves no
// point "at a spacing". The capture is still listed as the contributor (for staleness).
#include <cstdint>
#include <optional>

#include "policies/core/planner_info.h"
#include "policies/core/planner_params.h"
#include "sim/planner.h"

namespace ambisim {

class ConstantAmbientPlanner final : public Planner {
 public:
  enum class Mode { constant, hemisphere };

  static PlannerInfo constant_info();
  static PlannerInfo hemisphere_info();
  ConstantAmbientPlanner(Mode mode, const PlannerParams& params);

  std::string name() const override;
  nlohmann::json params() const override { return params_.to_json(); }

  // The one capture, at the camera before the first frame; plan() asks for it again only if it
  // never arrived.
  std::vector<CaptureRequest> preload(const FrameContext& ctx) override;
  std::vector<CaptureRequest> plan(const FrameContext& ctx) override;
  void started(std::uint64_t tag) override;
  void refused(std::uint64_t tag) override;
  void deliver(const FinishedProbe& probe) override;
  void update(const FrameContext& ctx) override;
  LookupResult lookup(const glm::dvec3& p) const override;
  PlannerStats stats() const override;

  // The truncation each mode applies (exposed for tests).
  static Sh9Rgb keep(Mode mode, const Sh9Rgb& sh);

 private:
  Mode mode_;
  PlannerParams params_;
  Sh9Rgb fallback_;  // the artist colour, already truncated
  std::uint64_t tag_ = 1;
  bool requested_ = false;  // a request is started or pending
  struct Held {
    std::uint64_t tag;
    Sh9Rgb sh;  // already truncated
    double data_time;
  };
  std::optional<Held> held_;
};

}  // namespace ambisim
