#pragma once
// `ambisim`: the project's own planner, designed from what the numbers showed (README,
// "Results"). The thesis' lattices spend the budget on coarse cells far above the road and
// pop when the interpolation pattern changes (thesis 7.6); the per-object alternative cannot
// keep up with 50 new objects per second (7.5.1). This planner:
// - captures where light is needed: at the objects the game will light (the receivers, which
//   the engine knows) and along the predicted camera path, at their height, never on a lattice
//   in the air;
// - spaces captures almost evenly (max(min_spacing_m, spacing_per_m x distance to the
//   predicted camera), 3 m out to 100 m by default): every object counts the same in the error
//   and the pops wherever it stands, and a LOD band of props 20-150 m ahead lives ~3 s, so a
//   coarse far field (0.2 per metre, like the coverage rule) cost forest_edge p95 12.2 vs 8.6;
// - plans ahead: positions are predicted one capture latency plus a look-ahead into the
//   future, along the road when the camera is on it (thesis 7.5.3);
// - never changes a lookup in a step: a new probe enters both the interpolation weights and
//   the value it holds gradually, starting from what lookups gave at its position (the
//   thesis' own remedy in 7.6: blend from the old to the new interpolation pattern), over
//   |ln(new / old irradiance)| / fade_rate seconds, at least fade_s and at most fade_max_s: a
//   large change spread over more frames stays under the visible step per frame instead of
//   popping on every frame of a short fade; probes leave by fading out over fade_s;
// - places probes closer together where a new probe disagrees with what its neighbours
//   predicted (the colour changes fast there: appendix B's untried idea);
// - refreshes by expected error when the light changes: each probe integrates how fast the
//   world says the light changes where it stands (the sun and sky everywhere, cloud shadows
//   drifting over it, lamps switching within their reach) into its expected relative error, its
//   drift; a probe whose drift passes refresh_drift competes for the budget with the objects'
//   need, the most stale first, and its new value fades in over the old one in place (the
//   interpolation pattern does not change);
// - near street lamps it captures the lamps' light as a second, additive set scaled by the
//   lamps' current state (thesis 7.5.3), so a lamp switching costs no recapture.
#include <cstdint>
#include <map>
#include <span>
#include <vector>

#include "policies/ambisim/far_field.h"
#include "policies/ambisim/probe_index.h"
#include "policies/core/coefficient_format.h"
#include "policies/core/half_set.h"
#include "policies/core/planner_info.h"
#include "policies/core/planner_params.h"
#include "policies/core/velocity_prediction.h"
#include "sim/planner.h"

namespace ambisim {

class DemandPlanner final : public Planner {
 public:
  static PlannerInfo info();
  explicit DemandPlanner(const PlannerParams& params);

  std::string name() const override { return "ambisim"; }
  nlohmann::json params() const override { return params_.to_json(); }
  std::vector<CaptureRequest> plan(const FrameContext& ctx) override;
  void started(std::uint64_t tag) override;
  void refused(std::uint64_t tag) override;
  void deliver(const FinishedProbe& probe) override;
  void update(const FrameContext& ctx) override;
  LookupResult lookup(const glm::dvec3& p) const override;
  void lookup_many(const LookupPoints& points, std::vector<LookupResult>& out) const override;
  PlannerStats stats() const override;
  // The same lookup by a linear scan over every probe, without the index: the reference the
  // index is tested against (equal to 1e-6) and the naive path of the benchmarks.
  LookupResult lookup_reference(const glm::dvec3& p) const;
  // Whether a lookup at p mixes in the far field (its bumps weigh under bump_confidence()). For
  // the benchmarks' profile.
  bool lookup_uses_far_field(const glm::dvec3& p) const;
  void set_receivers(const std::vector<ReceiverView>& receivers) override;
  // Voids every receiver's nearest-probe memo: the next plan() searches the index for each, the
  // reference the memos and their carrying over rebuilds are tested against.
  void forget_nearest_memos() { nearest_memo_.clear(); }
  void describe_nodes(std::vector<ProbeNodeView>& out) const override;

  // Required probe spacing at distance d from the focus (before local refinement), at the
  // budget last given to set_budget() (plan() gives it the frame's; 1 face per frame before).
  double required_spacing(double distance_m) const;
  void set_budget(double faces_per_frame);

 private:
  // 160 bytes: what a lookup needs inline, the set as the format stores it (fp16 bits, the
  // default; an fp32 set lives in the pool); the set a probe fades from and its lamp layer live
  // in the pool too, held only while fading and near lamps (memory per probe is a target).
  struct Probe {
    std::uint64_t tag = 0;
    glm::dvec3 position{0.0};
    double data_time = 0;
    double fade_in_start = -1;    // < 0: not started (starts at the first update after delivery)
    double fade_out_start = -1;   // >= 0: leaving
    Rgb light{1.0f};              // the scene's light level when it was captured (rescale)
    float spacing = 0;            // the spacing it was placed for
    float detail = 1;             // < 1 where the colour changes fast: neighbours come closer
    float fade_in = 0;            // its fade-in duration (0 = at once)
    float drift = 0;              // expected relative error since its data was captured
    float sensitivity = 1;        // its light's change over the world's reported rate (learnt)
    std::int32_t from = -1;       // pool slot: what lookups gave here before (while fading in)
    std::int32_t lamps = -1;      // pool slot: the lamps at full power (as stored), if any
    std::int32_t full = -1;       // pool slot: its set, when the format is fp32
    HalfSh9Rgb half;              // its set, when the format is fp16
    bool weight_fades_in = true;  // false after a refresh: only the value fades
    bool refreshing = false;      // a refresh capture for it is planned or in flight
    bool near_lamps = false;      // within the lamps' reach: their switching makes it stale
    bool has_lamps() const { return lamps >= 0; }
  };
  // The memory target counts on it (bench_planners' bytes_per_probe).
  static_assert(sizeof(Probe) <= 160, "a probe outgrew its 160 bytes");
  // Coefficient sets held apart from the probes, with slots reused in a fixed order.
  struct SetPool {
    std::vector<Sh9Rgb> sets;
    std::vector<std::int32_t> free;
    std::int32_t add(const Sh9Rgb& sh);
    void release(std::int32_t& slot);
    std::size_t held() const { return sets.size() - free.size(); }
  };
  struct Pending {
    glm::dvec3 position{0.0};
    double spacing = 0;
    double requested_time = 0;
    std::uint64_t refresh_of = 0;  // the probe this capture refreshes (0: a new probe)
    double drift_at_request = 0;   // that probe's drift when the refresh was requested
    Rgb light{1.0f};               // the scene's light level when it was requested
  };

  // The probe's set as stored (format applied), and sum += that set x k without building it.
  Sh9Rgb stored(const Probe& q) const;
  void add_stored(const Probe& q, const Rgb& k, Sh9Rgb& sum) const;
  // Stores sh in the format's precision: inline as fp16 bits, or in the pool as fp32.
  void store(Probe& q, const Sh9Rgb& sh);
  // How far a probe's fade-in has come, in [0, 1].
  double fade_in_fraction(const Probe& q) const;
  // Fade factor in [0, 1] of a probe at the current time (in and out).
  double presence(const Probe& q) const;
  // Kernel weight of a probe for a point at squared distance d2: a compact, smooth bump over
  // 1.5 spacings (support_radius), zero beyond.
  double kernel(const Probe& q, double d2) const;
  static double support_radius(const Probe& q) { return 1.5 * q.spacing; }
  // A probe's weight in the bump blend at squared distance d2: kernel x presence, 0 beyond its
  // support (the tail kernel reaches everywhere).
  double bump_weight(const Probe& q, double d2) const;
  // Adds w x what the probe shows now (shown(), without building it) to sum.
  void add_shown(const Probe& q, float w, Sh9Rgb& sum) const;
  // What an indexed lookup reads of a probe besides its position, spacing and coefficients,
  // fixed between update()s (the clock, the light and the lamps move only there): its
  // presence, and the factor on its coefficients (rescale x fade-in share) when that is all it
  // shows; `plain` false: it also shows a pool set (lamps, or the value it fades from), which
  // the lookup adds by add_shown. Saves a lookup's contributors the fade and rescale divisions.
  struct Look {
    float presence = 0.0f;
    Rgb scale{1.0f};
    bool plain = true;
  };
  Look look_of(const Probe& q) const;
  // Interpolated coefficients at p from the current probes; false if none is present. The
  // index finds the probes (the linear scan when `reference`); a batch passes its far-field
  // memo (the same answer from fewer finds).
  bool interpolate(const glm::dvec3& p, Sh9Rgb& out, LookupResult* meta, bool reference,
                   FarField::CornerMemo* memo = nullptr) const;
  // The lookup at p into r (default-constructed: the fields interpolate() leaves are zero).
  void lookup_into(const glm::dvec3& p, bool reference, FarField::CornerMemo* memo,
                   LookupResult& r) const;
  LookupResult lookup_with(const glm::dvec3& p, bool reference) const;
  // Faded out: weighs nothing, waits to be dropped from probes_.
  bool gone(const Probe& q) const;
  // Rebuilds the index and the far field over every probe (after the set changed).
  // `new_slot`: where each slot of the probes before the change went (-1: dropped), or empty
  // when none was dropped (slots unchanged).
  void reindex(std::span<const std::int32_t> new_slot = {});
  // Carries every receiver's memo of the current build over to the next one (see
  // nearest_memo_), before the index is rebuilt over probes_, whose probes from slot
  // `tail_from` on are the ones the rebuild adds.
  void carry_memos(std::span<const std::int32_t> new_slot, std::size_t tail_from);
  // A probe's far-field sums now: its presence w, w x what it shows, w x its data time.
  void add_far_sums(std::size_t i, FarField::Sums& s) const;
  // looks_ and the far field's sums from the probes' presences, values and the light now (after
  // update() and reindex()). A probe that is steady (fully present, its value faded in), was
  // steady at the last call and kept its value (deliver() marks a replaced one) looks and sums
  // as it did under the same light, so unless `all` (after a rebuild) or the light moved only
  // the others are redone.
  void follow_probes(bool all);
  // Whether lookups read the pyramid (not with the old kernel, whose tail reaches everywhere,
  // nor with far_field = scan): only then is it built and filled.
  bool uses_pyramid() const { return !kernel_tail_ && !far_scan_; }
  // The bump weight below which the far field is mixed in (alpha = weight / this).
  double bump_confidence() const;
  // far_field = scan: the faint tail of every probe, 1 / (1 + u^4), normalised (a linear scan).
  bool scan_tail(const glm::dvec3& p, FarField::Answer& out) const;
  // FarField::evaluate by its reference scan over every probe (lookup_reference's far field).
  bool evaluate_far_field_reference(const glm::dvec3& p, FarField::Answer& out) const;
  // Distance from c to the nearest probe or pending capture, and the local detail factor.
  double nearest_distance(const glm::dvec3& c, double* detail) const;
  // The staying probes of the unindexed tail from slot `from` on: n and best become the nearest
  // where one is nearer than best (ties keep the earlier).
  void nearest_in_tail(const glm::dvec3& c, std::size_t from, std::int64_t& n, double& best) const;
  // The probe's value at the lamps' current level (its lamp layer added).
  Sh9Rgb current(const Probe& q) const;
  // What the probe shows now: current() as it fades in from what was shown before.
  Sh9Rgb shown(const Probe& q) const;
  // Within the reach of a street lamp (horizontally, with a probe spacing to spare).
  bool near_lamps(const glm::dvec3& p) const;
  // Whether a capture at p renders a lamp layer.
  bool wants_lamp_layer(const glm::dvec3& p) const;
  Probe* find_probe(std::uint64_t tag);
  glm::dvec3 capture_point(const FrameContext& ctx, const glm::dvec3& p) const;

  PlannerParams params_;
  CoefficientFormat format_;
  PredictionSettings prediction_;
  double min_spacing_;
  double spacing_per_m_;
  double max_distance_;
  double height_;
  double fade_s_;
  double lifetime_s_;
  std::size_t max_probes_;
  bool by_need_;
  bool adapt_;
  bool budget_spacing_;
  double fade_rate_;
  double fade_max_s_;
  double adapt_de_;
  bool refresh_by_error_;
  double refresh_drift_;
  bool rescale_;
  bool learn_;
  bool lamp_layer_;  // the parameter: lamp layers where the world has lamps
  bool kernel_tail_;
  bool far_scan_;  // far_field = scan: the tail of every probe instead of the pyramid
  Sh9Rgb default_sh_;

  // The world's lamps (from the first frame's context).
  bool world_known_ = false;
  std::vector<glm::dvec3> lamps_;
  double lamp_reach_m_ = 0.0;
  bool lamp_layers_ = false;  // captures near lamps render a lamp layer
  double lamp_level_ = 0.0;
  Rgb light_now_{1.0f};  // the scene's light level now (LightingInfo's sun and sky)

  double now_ = 0.0;
  double budget_scale_ = 1.0;  // near spacing factor from the budget (set_budget)
  Focus focus_;
  std::vector<ReceiverView> receivers_;
  // Per receiver slot: the nearest staying indexed probe found for it, and for which receiver,
  // point and index build. Between rebuilds the indexed probes only leave (new ones join the
  // scanned tail), so while that probe stays it is still the nearest (ties go to the lower
  // slot in both): plan() then skips the index search, the bulk of its cost per receiver.
  // A rebuild adds the tail to the index and drops probes that left (not staying): the new
  // index's nearest is then the memo's probe or one of the tail's, so carry_memos() scans the
  // tail for each memo instead of voiding it (each voided memo cost a search at the next
  // plan(), about a quarter of BM_FrameReceivers/ambisim/1000's frame).
  // Likewise the tail: its probes only join (at the end) or leave, so the nearest of the tail
  // slots before tail_to, with the indexed one, stays the nearest of them while it stays, and
  // plan() scans only the probes delivered since (the whole tail, up to 32, for every receiver
  // was about a quarter of BM_FrameReceivers/ambisim/1000's receiver pass).
  // 48 bytes, as before the tail was memoised (the planner's bytes count them): slots and the
  // build in 32 bits. A memo of a build 2^32 rebuilds ago would pass for current, which takes
  // as many deliveries.
  static constexpr std::uint32_t kTailNotScanned = static_cast<std::uint32_t>(-1);
  struct NearestMemo {
    std::uint64_t id = 0;
    glm::dvec3 at{0.0};
    std::uint32_t build = 0;
    std::int32_t probe = -1;
    std::uint32_t tail_to = kTailNotScanned;  // tail slots [index size, tail_to) were scanned
    std::int32_t tail_probe = -1;             // the nearest of them and of `probe` (-1: none)
  };
  static_assert(sizeof(NearestMemo) == 48, "a receiver's memo outgrew its 48 bytes");
  std::vector<NearestMemo> nearest_memo_;
  std::uint64_t index_builds_ = 0;  // reindex() calls: a memo of an older build is void
  std::uint64_t next_tag_ = 1;
  std::vector<Probe> probes_;  // in delivery order
  std::vector<Look> looks_;    // beside probes_, as of the last update() or delivery
  SetPool pool_;
  ProbeIndex index_;  // over probes_[0, index_.size()); later ones are scanned
  FarField far_;      // over every probe, its sums as of the last update()
  // What the far field's last fill saw: which probes were steady (fully present, their value
  // faded in) and the light they were rescaled to. A steady probe under the same light adds
  // the same sums again, so follow_probes() redoes only the looks and cells of the others.
  std::vector<std::uint8_t> far_steady_;
  Rgb far_light_{0.0f};
  double far_lamp_level_ = 0.0;
  double far_time_ = 0.0;  // the clock at the last follow_probes(): a steady probe stays steady
                           // only while it does not run back
  std::map<std::uint64_t, Pending> planned_;  // returned by plan(), not yet started
  std::map<std::uint64_t, Pending> in_flight_;
};

}  // namespace ambisim
