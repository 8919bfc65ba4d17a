#pragma once
// The SHGraph machinery (thesis 8.4.2, Bilaga B), for a volume (Dim = 3, `shgraph`) or a
// ground sheet (Dim = 2, `shgraph2d`, thesis 8.5/9.3, D12). One concept: a hierarchy of cells
// split 3 per axis (27 or 9 children, created and removed together) with a coefficient anchor
// at each cell centre (the centre child shares its parent's anchor: same integer key, D10),
// made the first time planning considers the cell (about 4 in 10 cells of a split never are:
// they would hold an empty anchor of 330 B each),
// 2 x Dim same-depth neighbour links kept in pairs, a children-with-coefficients mask driving
// pruning, a root that grows when a capture is needed outside it and shrinks back (D9), a
// working depth from frame rate, budget and speed (D2), and a lookup of at most 2^Dim sets, one
// per octant (quadrant), interpolated by distance, going up a level while a level has none.
//
// Keys: anchor and node centres are integer triples in units of h = finest cell / 2 from a
// fixed origin (the first root's min corner). A node at depth d has half-size 3^(Dmax - d) in
// those units; the centre child has its parent's centre, hence its anchor. Depth may become
// negative after root growth. Positions are derived from keys, never the reverse.
#include <array>
#include <cstdint>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include "policies/thesis/coefficient_anchor.h"
#include "policies/thesis/shgraph_settings.h"
#include "sim/planner.h"

namespace ambisim {

// The anchor plus where it stands and how many nodes share it (the centre chain). Its x and y
// are its key's (ShGraphCore::anchor_point), so only its heights are stored: 24 bytes instead
// of the 80 of three points and a relocation (issue 15's memory target).
struct AnchorEntry {
  CoefficientAnchor anchor;
  // Where it is captured and its light is attributed (D14), in key units (h) from the origin:
  // what a lookup weighs by, beside the key's x and y (a volume only; a sheet weighs x and y).
  // capture_z converted once, not per lookup, and next to the set's flag, so that a lookup's
  // test of a cell reads one cache line of it.
  double capture_qz = 0.0;
  // Nominal: the node centre's (derivable from the key in a volume; on a sheet the ground's
  // height there, a world query).
  double position_z = 0.0;
  double capture_z = 0.0;   // moved up out of terrain and canopy (L318); the relocation is the
                            // difference from position_z
  double entered_at = 0.0;  // when its current run of sets began (the pattern blend, 7.6)
  std::int32_t refs = 0;
  bool dropped_in_solid = false;  // refused once for standing too deep inside a solid (L318)
};

template <int Dim>
class ShGraphCore {
 public:
  using Key = std::array<std::int64_t, Dim>;
  static constexpr int kChildren = Dim == 3 ? 27 : 9;
  static constexpr int kCentreChild = kChildren / 2;
  static constexpr int kLinks = 2 * Dim;
  static constexpr int kMaxLevels = 40;

  struct Node {
    Key key{};  // centre, in units of h
    std::int32_t depth = 0;
    std::int32_t parent = -1;
    std::int32_t first_child = -1;            // block of kChildren consecutive nodes, -1 = leaf
    std::array<std::int32_t, kLinks> link{};  // same-depth neighbours: -x,+x,-y,+y(,-z,+z)
    std::uint32_t children_with_coefficients = 0;  // thesis' set<int>, as a bit mask
    // Null until planning first considers the cell; then shared by every node with this key.
    AnchorEntry* anchor = nullptr;
  };

  explicit ShGraphCore(const ShGraphSettings& s);

  // The straightforward paths, kept as the reference for tests and bench/: update() visits
  // every anchor, stats() counts them, lookup() walks to each neighbour separately. Results
  // are identical either way (tests/policies/thesis/test_shgraph_naive.cpp).
  void set_naive(bool naive) { naive_ = naive; }

  std::vector<CaptureRequest> plan(const FrameContext& ctx);
  void started(std::uint64_t tag);
  void refused(std::uint64_t tag);
  void deliver(const FinishedProbe& probe);
  void update(const FrameContext& ctx);
  LookupResult lookup(const glm::dvec3& p) const;
  PlannerStats stats() const;
  void describe_nodes(std::vector<ProbeNodeView>& out) const;

  // Introspection for tests.
  int max_depth() const { return dmax_; }
  int working_depth() const { return d_eff_; }
  bool has_root() const { return !nodes_.empty(); }
  int root_depth() const { return nodes_.empty() ? 0 : nodes_[0].depth; }
  double root_size_now() const;       // metres
  double cell_size(int depth) const;  // metres
  const std::vector<Node>& nodes() const { return nodes_; }
  bool node_live(std::int32_t i) const;
  glm::dvec3 node_centre(std::int32_t i) const;  // metres (z: the anchor's, on a sheet)
  // The anchor at a node centre (null: no node there at any depth).
  const CoefficientAnchor* anchor_at(const glm::dvec3& p, int depth) const;
  std::int64_t anchor_count() const { return static_cast<std::int64_t>(anchors_.size()); }
  // Sets never captured because they stood deeper inside terrain or canopy than the relocation
  // allows (each saves a capture's faces).
  std::int64_t dropped_in_solids() const { return dropped_in_solids_; }

 private:
  using Q = std::array<double, Dim>;  // a position in h units from the origin

  Q to_q(const glm::dvec3& p) const;
  // Where a lookup weighs an anchor, in key units: its key's x and y and, in a volume, its
  // capture height.
  static Q capture_q(const Key& key, const AnchorEntry& e) {
    Q at;
    for (int a = 0; a < Dim; ++a) at[a] = static_cast<double>(key[a]);
    if constexpr (Dim == 3) at[2] = e.capture_qz;
    return at;
  }
  std::int64_t half(int depth) const { return pow3_[dmax_ - depth]; }
  bool contains(std::int32_t i, const Q& q) const;
  int child_containing(std::int32_t i, const Q& q) const;
  glm::dvec3 anchor_position(const Key& key) const;
  glm::dvec3 capture_position(const glm::dvec3& nominal) const;
  // An anchor's point at one of its stored heights (position_z, capture_z): x and y from its key,
  // the same values anchor_position() gave it.
  glm::dvec3 anchor_point(const Key& key, double z) const;

  // The anchors are made lazily, and the invariant is: an entry exists for a key iff some live
  // node with that key was considered by plan(), and then every live node with the key points
  // to it (refs counts them); otherwise they all hold null. Nodes with one key form a centre
  // chain (a node, its centre child, that one's centre child, ...).
  // The existing anchor of a new node's key, with one more reference (null: none yet).
  AnchorEntry* share_existing(const Key& key);
  // Node i's anchor, made now if its chain has none (position and capture point computed as
  // they would have been at the node's creation: they depend on the key and the world only).
  AnchorEntry& materialize(std::int32_t i);
  // Node i gives up its key (its children released before it): the anchor goes with the last
  // node of its chain, which is also when the fill memo counts a forgotten cell.
  void release_key(std::int32_t i);
  // Drops an anchor from the update lists before its entry is erased.
  void forget(AnchorEntry* e);
  void set_coefficients(AnchorEntry* e, const Sh9Rgb& sh, const FinishedProbe& probe,
                        const Sh9Rgb* fade_from, double fade_from_time);
  std::int32_t alloc_block();
  void init_child(std::int32_t parent, int c, std::int32_t slot);
  void link_children(std::int32_t parent);
  void expand(std::int32_t i);
  void collapse(std::int32_t i);
  void release_node(std::int32_t i);
  void move_node(std::int32_t from, std::int32_t to);
  bool grow_towards(const Q& q);
  void shrink_root(int child);
  std::int32_t ensure_node(const Q& q, int depth);
  std::int32_t neighbour(std::int32_t i, const std::array<int, Dim>& offset) const;
  // The node and its same-depth neighbours, index sum (o[a] + 1) 3^a (-1 where none).
  using Neighbourhood = std::array<std::int32_t, kChildren>;
  void neighbourhood(std::int32_t i, Neighbourhood& out) const;
  void neighbourhood_naive(std::int32_t i, Neighbourhood& out) const;
  std::int32_t find_deepest(const Q& q, std::array<std::int32_t, kMaxLevels>& path,
                            int* count) const;
  std::uint32_t refresh_masks(std::int32_t i, const Focus& focus, bool* in_flight);
  bool protected_node(std::int32_t i, const Focus& focus) const;
  void update_working_depth(const FrameContext& ctx);
  double ground_at(double x, double y) const;
  // A lookup's point and its descent, found once: the pattern blend's coarser answers
  // (lookup_into's recursion) read the same path from a shallower level.
  struct LookupPath {
    Q q{};
    // Left uninitialised: only [0, count) is written and read (zeroing 160 bytes per lookup
    // showed in its profile).
    std::array<std::int32_t, kMaxLevels> nodes;
    int count = 0;
    bool outside = false;  // beyond the root: the answer is only a coarse default
  };
  // lookup() without its fallback, from the levels shallower than above_depth: false when no
  // set serves the point (r is then untouched).
  bool lookup_into(const LookupPath& path, LookupResult& r,
                   int above_depth = std::numeric_limits<int>::max()) const;

  ShGraphSettings s_;
  int dmax_ = 0;
  double h_ = 1.0;
  glm::dvec3 origin_{0.0};
  std::array<std::int64_t, kMaxLevels> pow3_{};
  std::vector<Node> nodes_;  // [0] = root; then blocks of kChildren
  std::vector<std::int32_t> free_blocks_;
  std::map<Key, AnchorEntry> anchors_;
  // What update() must visit (the rest of the anchors' update() would change nothing): anchors
  // holding a set, by the creation time of their newest set (only old sets can expire or ask
  // for renewal), and anchors mid-fade. by_age_ holds exactly the anchors with coefficients.
  std::set<std::pair<double, AnchorEntry*>> by_age_;
  std::vector<AnchorEntry*> fading_;
  double margin_prev_s_ = 0.0;  // the renewal margin of the previous update()
  LightClock clock_;            // set ages under changing light (the thesis' refresh rule)
  bool naive_ = false;
  struct InFlight {
    Key key{};
    double requested_time = 0.0;
  };
  std::map<std::uint64_t, InFlight> pending_;    // returned by plan(), not yet started
  std::map<std::uint64_t, InFlight> in_flight_;  // started, not yet delivered
  std::uint64_t next_tag_ = 1;
  const WorldQueries* world_ = nullptr;
  double now_ = 0.0;
  int d_eff_ = -1;
  std::int64_t dropped_in_solids_ = 0;
  // The budget fill's memo (plan()): its last scan found nothing, from this cell, with this
  // many anchors forgotten so far.
  bool fill_empty_ = false;
  Key fill_key_{};
  int fill_level_ = 0;
  std::int64_t forgotten_ = 0;
  std::int64_t fill_forgotten_ = 0;
  double shrink_since_ = -1.0;
};

// No `extern template class` here: the members are instantiated one by one in the files that
// define them (shgraph_*.cpp), so an extern declaration of the whole class would leave the
// inline members in this header (half, ...) without a definition wherever a compiler does not
// inline them (clang's sanitizer build did not link).

}  // namespace ambisim
