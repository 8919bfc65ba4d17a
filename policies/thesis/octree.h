#pragma once
// `octree` and `octree+vp`: the thesis' first structure (8.4.1, L510-558; THESIS_NOTES section
// 5, decisions D1, D3, D10, D11, D15).
//
// Structure. A cube root split into 8 equal children. Coefficient sets live at node CORNERS,
// keyed on an integer lattice (policies/core/lattice_key.h), so neighbouring nodes share one set
// per corner and a split adds at most 19 lattice points. The root is the smallest
// power-of-two cube of min_cell_m cells covering the world bounds (root=world, the thesis'
// fixed top node), or a root_m cube centred on the first camera position (root=camera, also
// used when no world is known). Outside the root nothing is captured and lookups fall back.
//
// Search (L526, D1). From the root down the path to the leaf containing the focus (the camera;
// with +vp first the predicted position p*, then the camera), the first corner without a set
// and not in flight (or flagged for renewal) is captured, corners of one node taken nearest to
// the focus first. A leaf whose 8 corners all hold sets splits, down to min_cell_m. So
// refinement is coarse first, the order the thesis reports as a failure (L550). A corner
// whose capture would have to move out of terrain or canopy by more than half the asking
// node's cell is never captured and counts as present for the split (D14, DDGI's
// classification); lookups renormalise over the corners that hold sets.
//
// Lookup (D3). lookup=trilinear: trilinear interpolation over the 8 corners of the deepest
// COMPLETE node on the path to p (a parent is complete when it splits; when eviction or expiry
// broke that, the search climbs further). lookup=octant: the thesis' scheme (L532): corners on
// the leaf box (including T-junction corners of finer neighbours), the nearest per octant
// around p, inverse-distance weights (D4); a node lacking an octant climbs to its parent.
// Before any node is complete (the first root captures) the sets present are blended with
// renormalised weights and flagged fell_back; outside the root: black, fell_back.
//
// Retention (D11). retention=cap: at most max_sets sets (the thesis' 300 = 30 fps x 60 s / 6).
// Beyond it, sets are evicted that belong to nodes far from the camera in the TREE: the
// shallowest common ancestor of the owning node (the node that requested the set) with the
// camera's leaf first, then the spatially farthest; sets owned by the camera's own path (root
// down to its leaf: "sets near the root are the most important to keep") are kept. This
// deletes sets next to the camera owned across a coarse face, as the thesis observed (L554).
// retention=lifetime: sets expire lifetime_s after their request (D6) and are re-requested
// renew_margin_s + 2 capture latencies before (D7), as the thesis' fix (L556).
// Under changing light with refresh=rate (an option, default lifetime) renewals go by the light
// clock (policies/core/light_clock.h, the thesis' refresh rule of 7.5.3): sets are renewed when the
// light may have changed by refresh_tolerance, in either retention (cap keeps deciding which
// sets stay); under still light nothing changes.
//
// No fade: the octree inserts new sets directly (the thesis added fading only in SHGraph).
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <vector>

#include "policies/core/coefficient_format.h"
#include "policies/core/lattice_key.h"
#include "policies/core/light_clock.h"
#include "policies/core/planner_info.h"
#include "policies/core/planner_params.h"
#include "policies/core/velocity_prediction.h"
#include "sim/planner.h"

namespace ambisim {

class OctreePlanner final : public Planner {
 public:
  static PlannerInfo info();     // "octree"
  static PlannerInfo vp_info();  // "octree+vp"
  OctreePlanner(const PlannerParams& params, bool predict);

  std::string name() const override { return prediction_.enabled ? "octree+vp" : "octree"; }
  nlohmann::json params() const override { return params_.to_json(); }

  std::vector<CaptureRequest> plan(const FrameContext& ctx) override;
  void started(std::uint64_t tag) override;
  void refused(std::uint64_t tag) override;
  void deliver(const FinishedProbe& probe) override;
  void update(const FrameContext& ctx) override;
  // spacing_m = edge length of the node interpolated in; contributors = its corners' captures.
  LookupResult lookup(const glm::dvec3& p) const override;
  PlannerStats stats() const override;
  // Every node (centre, half extent, depth; has_data = all 8 corners hold sets, sh = their
  // mean), then every corner with a set or in flight as a zero-size entry.
  void describe_nodes(std::vector<ProbeNodeView>& out) const override;

  // Diagnostics for tests and charts (the failure reports of L554-556).
  struct Counters {
    std::int64_t splits = 0;
    std::int64_t evictions = 0;              // cap
    std::int64_t evictions_near_camera = 0;  // within one camera-leaf cell of the camera
    std::int64_t rerequested_within_1s = 0;  // evicted/expired, then requested again within 1 s
    std::int64_t expiries = 0;               // lifetime
    std::int64_t expiries_near_camera = 0;
    std::int64_t renewals = 0;  // re-requests of sets that still held data
  };
  const Counters& counters() const { return counters_; }
  bool has_root() const { return root_ready_; }
  const OctreeLattice& lattice() const { return lattice_; }
  std::int64_t live_sets() const { return live_; }
  bool corner_has_data(const LatticeKey& k) const;

 private:
  struct Corner {
    Sh9Rgb sh;              // as stored (format_.store)
    std::uint64_t tag = 0;  // capture now in flight, or the one that produced sh
    std::uint64_t data_tag = 0;
    double data_time = 0.0;  // request time of the data (D6)
    NodeKey owner;           // the node that last requested it (tree distance for the cap)
    bool has_data = false;
    bool in_flight = false;  // pending (returned by plan) or started
    bool renew = false;      // lifetime: re-request before expiry
  };
  enum class Lookup { trilinear, octant };

 public:
  // Corners never captured because they stood too deep inside a solid.
  std::int64_t dropped_in_solids() const { return dropped_in_solids_; }

 private:
  void init_root(const FrameContext& ctx);
  // The deepest existing node containing p (p inside the root).
  NodeKey leaf_at(const glm::dvec3& p) const;
  bool is_split(const NodeKey& n) const { return split_.count(n) != 0; }
  bool complete(const NodeKey& n) const;
  bool needs_capture(const LatticeKey& k) const;
  // One search from the root toward `target` (splitting complete leaves on the way): the
  // corner to capture and the node asking for it.
  std::optional<std::pair<LatticeKey, NodeKey>> search(const glm::dvec3& target);
  glm::dvec3 capture_position(const LatticeKey& k) const;
  // A corner whose capture would move out of a solid by more than half the cell of the node
  // asking (L318): never captured, and counted as present for the node's completeness (DDGI's
  // probe classification). The lift is computed once per corner (search()).
  bool inside_solid(const LatticeKey& k, int depth);
  bool known_inside_solid(const LatticeKey& k, int depth) const;
  void enforce_cap();
  void expire();
  // Drops a corner's set (and the entry unless a capture for it is in flight).
  void remove_set(std::map<LatticeKey, Corner>::iterator it);
  // Collapses splits whose 19 added points all lost their sets, from the nodes around removed
  // corners upward (so memory follows the sets, and only changed nodes are visited).
  void prune();
  NodeKey camera_leaf() const;
  LookupResult lookup_trilinear(const glm::dvec3& p) const;
  LookupResult lookup_octant(const glm::dvec3& p) const;
  // Whatever sets the node's corners hold, trilinear weights renormalised (no complete node).
  LookupResult lookup_partial(const NodeKey& n, const glm::dvec3& p) const;

  PlannerParams params_;
  CoefficientFormat format_;
  PredictionSettings prediction_;
  double min_cell_m_;
  bool root_from_world_;
  double root_m_;
  bool cap_;
  std::int64_t max_sets_;
  double lifetime_s_;
  double renew_margin_s_;
  LightClock clock_;  // the thesis' refresh rule: set ages under changing light
  double lift_m_;
  Lookup lookup_mode_;

  bool root_ready_ = false;
  OctreeLattice lattice_;
  const WorldQueries* world_ = nullptr;
  double now_ = 0.0;
  double latency_s_ = 0.0;
  glm::dvec3 camera_{0.0};
  std::uint64_t next_tag_ = 1;
  std::int64_t live_ = 0;                          // corners holding a set
  std::map<LatticeKey, Corner> corners_;           // with a set or in flight
  std::set<NodeKey> split_;                        // nodes with children
  std::map<std::uint64_t, LatticeKey> tags_;       // in flight: tag -> corner
  std::set<std::uint64_t> pending_;                // returned by plan(), not yet started
  std::map<LatticeKey, double> recently_removed_;  // for rerequested_within_1s
  std::set<LatticeKey> removed_since_prune_;
  struct SolidCheck {
    double lift_m = 0.0;   // capture_position's move out of terrain or canopy
    bool dropped = false;  // refused at least once
  };
  std::map<LatticeKey, SolidCheck> lifts_;  // every corner search() examined
  std::int64_t dropped_in_solids_ = 0;
  Counters counters_;
};

}  // namespace ambisim
