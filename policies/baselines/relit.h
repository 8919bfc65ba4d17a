#pragma once
// `relit`: probes captured once and relit every frame from the current sun and sky, the way
// games follow a time of day without recapturing (Far Cry 3's deferred radiance transfer
// volumes: a sky term through the probe's sky visibility plus a sun-and-sky bounce term, both
// relit at run time; Unity APV's sky occlusion: a stored sky visibility times the current sky).
//
// Placement, lookup and fade are `nearest`'s (a capture at the camera whenever no finished or
// in-flight probe lies within spacing_m, at most one request per frame; the nearest probe
// answers; a new probe fades in over blend_s from the value lookups had at its position), with
// no lifetime: a probe is captured once and never again for lighting. Beyond max_probes the
// probe farthest from the camera goes, so a place is captured again only when the camera comes
// back to it (position coverage). Under light that does not change relit answers exactly what
// `nearest` (with a lifetime longer than the run) answers, so the two differ by the relighting
// alone.
//
// What a capture gives is the full radiance L at the probe (the sky it sees and the light its
// surroundings bounce, the sun disc excluded), not a transfer. A game bakes the transfer with
// its geometry; here it is estimated at delivery from the capture and what the engine knows of
// its own lighting at the capture's time t0 (WorldQueries::lighting: the sky's SH S0, the sun's
// irradiance E0 and direction s0), with one fixed decomposition:
//   L = v S0 + B
// - the sky seen, v S0: the current sky through a scalar sky visibility v (APV's sky occlusion
//   with one coefficient), estimated as the capture's upward irradiance over the open sky's,
//   in luminance, clamped to [0, 1]: v = Y(E_up(L)) / Y(E_up(S0));
// - the bounce, B = L - v S0: everything else (the ground below and the slopes, walls and
//   canopy above the horizon), taken to be lit like an unshadowed horizontal plane,
//   G = E_sky_up + E_sun max(0, s.z) per channel, so its transfer B / G0 (albedo times view
//   factor) is what the sun does not change. Splitting B into a sky-lit share E_sky_up0 / G0
//   relit by E_sky_up(t) / E_sky_up0 and a sun-lit share relit by E(t) s(t).z / (E0 s0.z)
//   gives the same B G(t) / G0, which also holds when the sun was down at t0.
// Relit at time t (per channel, g = G(t) / G0):
//   L(t) = L + v (S(t) - S0) + (g - 1) (L - v S0)
// written as a correction of the capture, so that unchanged light returns the capture bit for
// bit; when the sun and sky both scale by k it returns k L; a change of the sun's colour moves
// the bounce alone; a change of the sky's colour or shape moves the sky term through v and the
// bounce through E_sky_up.
//
// What it cannot follow, by construction (as the games' relit probes cannot): anything local.
// Cloud shadows (S is the sky at its mean cover and E the clear sun), street lamps (their light
// in a capture counts as bounce and is relit with the sun and sky: dimmed at dusk, though the
// lamps stay on), fog rising (the capture's fog stays), and the shadows the probe saw at t0,
// which stay where they were while the sun moves (the bounce's transfer freezes the sun
// visibility of the ground seen). A fixed split is used rather than a fitted SH visibility
// (the SH triple product): one capture under one light cannot tell the sky seen from a surface
// lit like it, and a scalar visibility keeps the relighting exact for the uniform changes above.
#include <cstdint>
#include <map>
#include <optional>
#include <vector>

#include "policies/core/coefficient_format.h"
#include "policies/core/planner_info.h"
#include "policies/core/planner_params.h"
#include "sim/planner.h"

namespace ambisim {

// What a relit probe keeps of its capture (the decomposition above).
struct RelitTransfer {
  Sh9Rgb captured;              // L, as stored
  Sh9Rgb sky0;                  // S0: the sky's SH at the capture's time, as stored
  Rgb ground0{0.0f};            // G0: an unshadowed horizontal plane's irradiance then
  float sky_visibility = 0.0f;  // v in [0, 1]
  bool relightable = false;     // false: light that never changes, only `captured` is kept
};

// G = E_sky_up + E_sun max(0, s.z): the irradiance of an unshadowed horizontal plane.
Rgb relit_ground_irradiance(const LightingInfo& light);
// v = Y(E_up(captured)) / Y(E_up(sky)) clamped to [0, 1]; 0 when the sky gives no light.
float relit_sky_visibility(const Sh9Rgb& captured, const Sh9Rgb& sky);
// The transfer of a capture taken under `at_capture` (values stored through `format`).
RelitTransfer relit_transfer(const Sh9Rgb& captured, const LightingInfo& at_capture,
                             const CoefficientFormat& format = {});
// The probe's radiance under `now`, the current sky taken through `format` as the stored one
// was (the result itself not yet stored).
Sh9Rgb relight(const RelitTransfer& t, const LightingInfo& now,
               const CoefficientFormat& format = {});

class RelitPlanner final : public Planner {
 public:
  static PlannerInfo info();
  explicit RelitPlanner(const PlannerParams& params);

  std::string name() const override { return "relit"; }
  nlohmann::json params() const override { return params_.to_json(); }

  std::vector<CaptureRequest> plan(const FrameContext& ctx) override;
  void started(std::uint64_t tag) override;
  void refused(std::uint64_t tag) override;
  void deliver(const FinishedProbe& probe) override;
  // Relights every probe at ctx.time (when the world's light changes), then fades and caps.
  void update(const FrameContext& ctx) override;
  // As `nearest`: spacing_m = distance to the probe used; contributors: the probe (and,
  // mid-fade, the probe it fades from, weighted 1 - t).
  LookupResult lookup(const glm::dvec3& p) const override;
  PlannerStats stats() const override;
  void describe_nodes(std::vector<ProbeNodeView>& out) const override;

 private:
  struct Probe {
    std::uint64_t tag = 0;
    glm::dvec3 position{0.0};
    double data_time = 0.0;  // request time (D6), as `nearest`
    RelitTransfer transfer;
    Sh9Rgb relit;  // the transfer under the light of the last update, as stored
    // Fade-in from the lookup value at its position at delivery (`from`), which follows the
    // relighting of the probe it came from (`from_tag`) by the change of that probe's relit
    // value since delivery (`from_base`).
    bool fading = false;
    bool fade_start_known = false;
    double fade_start = 0.0;
    Sh9Rgb from;
    Sh9Rgb from_base;
    Sh9Rgb from_now;
    std::uint64_t from_tag = 0;  // 0: `from` came from no probe
    double from_data_time = 0.0;
  };
  struct InFlight {
    glm::dvec3 position{0.0};
    double requested_time = 0.0;
  };

  std::optional<std::size_t> nearest(const glm::dvec3& p, double* distance) const;
  const Probe* find(std::uint64_t tag) const;
  float fade_weight(const Probe& q) const;
  void enforce_cap();
  // The light relit probes follow: none when the world's light never changes (or is unknown).
  bool relighting(const WorldQueries* world) const;

  PlannerParams params_;
  double spacing_m_;
  std::size_t max_probes_;
  double blend_s_;
  CoefficientFormat format_;

  double now_ = 0.0;
  glm::dvec3 camera_{0.0};
  const WorldQueries* world_ = nullptr;  // the last frame's (owned by the simulator)
  std::optional<LightingInfo> light_;    // the light at now_, when relighting
  std::uint64_t next_tag_ = 1;
  std::vector<Probe> probes_;                    // in delivery order
  std::map<std::uint64_t, InFlight> pending_;    // returned by plan(), not yet started
  std::map<std::uint64_t, InFlight> in_flight_;  // started, not yet delivered
};

}  // namespace ambisim
