// SHGraph's planning: the working depth from speed and frame rate (D2), and which cells to
// capture this frame: missing and expiring sets around the (predicted) camera, the working
// depth first (D21; coarse_first: the first version's order), the road ahead one level finer
// with +route (D20), then widened at the working depth, then the budget fill (D22). Cells
// deeper inside a solid than half a cell are never asked for (D14).
#include "policies/thesis/shgraph_core.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <tuple>
#include <vector>

#include <glm/geometric.hpp>

namespace ambisim {

template <int Dim>
void ShGraphCore<Dim>::update_working_depth(const FrameContext& ctx) {
  const double fps = s_.fps_min > 0.0 ? s_.fps_min : (ctx.dt > 0.0 ? 1.0 / ctx.dt : 60.0);
  glm::dvec3 v = ctx.camera_velocity;
  if constexpr (Dim == 2) v.z = 0.0;  // the sheet only sees horizontal motion
  const double speed = glm::length(v);
  if (d_eff_ < 0 || ctx.camera_cut) {
    d_eff_ = depth_for_speed(speed, fps, ctx.faces_per_frame, s_);
    return;
  }
  // +-20 % speed hysteresis (D2): change level only once the speed has clearly left the band.
  const int lo = depth_for_speed(speed * 1.2, fps, ctx.faces_per_frame, s_);
  const int hi = depth_for_speed(speed / 1.2, fps, ctx.faces_per_frame, s_);
  d_eff_ = std::clamp(d_eff_, lo, hi);
}

template <int Dim>
std::vector<CaptureRequest> ShGraphCore<Dim>::plan(const FrameContext& ctx) {
  world_ = ctx.world;
  now_ = ctx.time;
  pending_.clear();  // anything neither started nor refused last frame never started
  update_working_depth(ctx);
  if (ctx.startable_captures <= 0) return {};
  const Focus focus = make_focus(ctx, s_.prediction);
  if (nodes_.empty()) {
    // The first root is centred on the camera; its min corner is the fixed key origin (D10).
    origin_ = focus.now;
    for (int a = 0; a < Dim; ++a) origin_[a] = focus.now[a] - 0.5 * s_.root_size_m;
    if constexpr (Dim == 2) origin_.z = 0.0;
    if constexpr (Dim == 3) {
      // The root's centre is the centre cell of every depth, so this puts a cell centre of
      // every depth at anchor_height_m above the ground here.
      if (s_.anchor == LatticeAnchor::ground && world_ != nullptr && world_->ground_height) {
        origin_.z = world_->ground_height(focus.now.x, focus.now.y) + s_.anchor_height_m -
                    0.5 * s_.root_size_m;
      }
    }
    Node root;
    root.key.fill(pow3_[dmax_]);
    root.link.fill(-1);
    nodes_.push_back(root);
    // Its anchor is made when planning first considers it, as every cell's.
  }
  const Q q_now = to_q(focus.now);
  const Q q_ahead = to_q(focus.ahead);
  while (!contains(0, q_now) && grow_towards(q_now)) {
  }
  while (!contains(0, q_ahead) && grow_towards(q_ahead)) {
  }

  struct Candidate {
    int tier;      // 0 missing near, 1 re-request near, 2 missing widened, 3 re-request widened
    int level;     // coarse_first: the level; near_first: minus the level (finest first)
    int rank;      // near_first: the split priority (centre, corners, faces, edges; L572)
    double score;  // distance to the focus, or capture time for re-requests (oldest first)
    Key key;
    glm::dvec3 capture;
    bool operator<(const Candidate& o) const {
      return std::tie(tier, level, rank, score, key) <
             std::tie(o.tier, o.level, o.rank, o.score, o.key);
    }
  };
  const bool near_first = s_.order == CandidateOrder::near_first;
  std::vector<Candidate> cands;
  std::set<Key> seen;
  // Cells whose set would stand deeper inside a solid than the relocation allows (L318).
  const auto inside_solid = [&](AnchorEntry& e, int level) {
    const double relocation_m = e.capture_z - e.position_z;
    if (relocation_m <= s_.max_relocation_cells * cell_size(level)) return false;
    if (!e.dropped_in_solid) {
      e.dropped_in_solid = true;
      ++dropped_in_solids_;
    }
    return true;
  };
  const auto consider = [&](std::int32_t j, int near_tier, int level, int rank) {
    if (j < 0 || nodes_[j].depth != level) return;
    AnchorEntry& e = materialize(j);
    // A shared centre too deep for a fine cell may still serve the coarser cell it centres.
    if (e.anchor.in_flight() || inside_solid(e, level)) return;
    if (!seen.insert(nodes_[j].key).second) return;
    const Key& key = nodes_[j].key;
    glm::dvec3 c = anchor_point(key, e.position_z);
    if constexpr (Dim == 2) c.z = focus.now.z;  // horizontal distance on the sheet
    const int order_level = near_first ? -level : level;
    if (!e.anchor.has_coefficients()) {
      cands.push_back({near_tier, order_level, near_first ? rank : 0, focus.distance(c), key,
                       anchor_point(key, e.capture_z)});
    } else if (e.anchor.need_new()) {
      cands.push_back(
          {near_tier + 1, 0, 0, e.anchor.creation_time(), key, anchor_point(key, e.capture_z)});
    }
  };
  // The thesis' priority inside a split (L572): the centre, then the 8 corners, the 6 faces,
  // the 12 edges (by how many axes are offset: 0, Dim, 1, then the rest).
  const auto split_rank = [](int offset_axes) {
    if (offset_axes == 0) return 0;
    if (offset_axes == Dim) return 1;
    return offset_axes == 1 ? 2 : 3;
  };
  // Cells at `level` within Chebyshev radius r (exactly r when ring) of the focus segment;
  // with `slab`, at most one cell above or below it (the offsets are then enumerated directly,
  // 8r per layer, so wide rings stay cheap).
  std::vector<std::array<int, Dim>> offsets;
  const auto region = [&](int level, int r, bool ring, int near_tier, bool slab) {
    offsets.clear();
    if (slab) {
      const int vz = Dim == 3 ? std::min(r, 1) : 0;
      for (int z = -vz; z <= vz; ++z) {
        for (int x = -r; x <= r; ++x) {
          for (int y = -r; y <= r; ++y) {
            const int cheb = std::max(std::abs(x), std::abs(y));
            if (ring && cheb != r) {
              y = std::abs(x) == r ? y : r - 1;  // jump to the far edge of the ring
              continue;
            }
            std::array<int, Dim> o{};
            o[0] = x;
            o[1] = y;
            if constexpr (Dim == 3) o[2] = z;
            offsets.push_back(o);
          }
        }
      }
    } else {
      const int side = 2 * r + 1;
      int cells = 1;
      for (int a = 0; a < Dim; ++a) cells *= side;
      for (int n = 0; n < cells; ++n) {
        std::array<int, Dim> o{};
        int rest = n, cheb = 0;
        for (int a = 0; a < Dim; ++a) {
          o[a] = rest % side - r;
          rest /= side;
          cheb = std::max(cheb, std::abs(o[a]));
        }
        if (!ring || cheb == r) offsets.push_back(o);
      }
    }
    const double cell_q = 2.0 * static_cast<double>(half(level));
    double len = 0.0;
    for (int a = 0; a < Dim; ++a) len = std::max(len, std::abs(q_ahead[a] - q_now[a]));
    const int samples = 1 + static_cast<int>(std::ceil(len / cell_q));
    for (int s = 0; s <= samples; ++s) {
      const double t = static_cast<double>(s) / samples;
      Q q;
      for (int a = 0; a < Dim; ++a) q[a] = q_now[a] + t * (q_ahead[a] - q_now[a]);
      const std::int32_t centre = ensure_node(q, level);
      if (centre < 0 || nodes_[centre].depth != level) continue;
      const Key ck = nodes_[centre].key;
      for (const auto& o : offsets) {
        int axes = 0;
        for (int a = 0; a < Dim; ++a) axes += o[a] != 0;
        Q p;
        for (int a = 0; a < Dim; ++a) p[a] = static_cast<double>(ck[a]) + o[a] * cell_q;
        if constexpr (Dim == 3) {
          if (s_.skip_underground && world_ != nullptr && world_->ground_height) {
            const double x = origin_.x + p[0] * h_, y = origin_.y + p[1] * h_;
            const double top = origin_.z + (p[2] + 0.5 * cell_q) * h_;
            if (top < world_->ground_height(x, y)) continue;  // the floor (L307)
          }
        }
        consider(ensure_node(p, level), near_tier, level, split_rank(axes));
      }
    }
  };
  const auto wanted = static_cast<std::size_t>(ctx.startable_captures);
  const int top = std::max(nodes_[0].depth, 0);
  // The 3^Dim neighbourhood at every level from the root to the working depth: sufficient
  // resolution all around the (predicted) camera at once, far nodes later (L566, L552).
  // At the normal root size and above only the focus cell itself: its neighbours are not part
  // of the normal graph, and capturing them would keep a grown root from ever shrinking (D9).
  // near_first visits the working depth first, so a centre shared down the levels (D10) is a
  // candidate of the finest cell it is the centre of.
  for (int i = 0; top + i <= d_eff_; ++i) {
    const int level = near_first ? d_eff_ - i : top + i;
    region(level, level <= 0 ? 0 : 1, false, 0, false);
  }
  // Road knowledge (L316): the road ahead one level finer, where the car will be.
  if (s_.road_refine_levels > 0 && s_.prediction.route) {
    const int fine = std::min(dmax_, std::max(d_eff_, 0) + s_.road_refine_levels);
    for (const glm::dvec3& p :
         road_ahead(ctx, s_.road_ahead_s, 0.5 * cell_size(fine), s_.prediction.route_snap_m)) {
      const Q q = to_q(p);
      const std::int32_t j = ensure_node(q, fine);
      if (j >= 0) consider(j, 0, fine, 0);
    }
  }
  // Then widen at the working depth (L420).
  for (int r = 2; d_eff_ > 0 && r <= s_.widen_cells && cands.size() < wanted; ++r) {
    region(d_eff_, r, true, 2, false);
  }
  // Budget still left: new sets ring by ring at max(working depth, 1), a slab one cell up and
  // down, inside the root (L574), at most fill_cells rings and fill_radius_m out. A fill that
  // found nothing is not repeated until the focus enters another cell of that level or a set
  // is dropped (a parked camera would otherwise scan the same full rings every frame).
  if (s_.fill_budget && cands.size() < wanted) {
    const int level = std::min(dmax_, std::max(d_eff_, 1));
    const int first = d_eff_ > 0 ? s_.widen_cells + 1 : 1;
    const int reach =
        std::min(s_.fill_cells, static_cast<int>(std::floor(s_.fill_radius_m / cell_size(level))));
    const std::int32_t here = ensure_node(q_now, level);
    const Key here_key = here >= 0 ? nodes_[here].key : Key{};
    const bool same = fill_empty_ && here_key == fill_key_ && level == fill_level_ &&
                      forgotten_ == fill_forgotten_;
    if (!same) {
      const std::size_t before = cands.size();
      for (int r = first; r <= reach && cands.size() < wanted; ++r) {
        region(level, r, true, 2, true);
      }
      fill_empty_ = cands.size() == before;
      fill_key_ = here_key;
      fill_level_ = level;
      fill_forgotten_ = forgotten_;
    }
  }
  std::sort(cands.begin(), cands.end());
  std::vector<CaptureRequest> out;
  for (const auto& c : cands) {
    if (out.size() >= wanted) break;
    const std::uint64_t tag = next_tag_++;
    pending_[tag] = {c.key, ctx.time};
    out.push_back({c.capture, tag});
  }
  return out;
}

template <int Dim>
void ShGraphCore<Dim>::started(std::uint64_t tag) {
  auto it = pending_.find(tag);
  if (it == pending_.end()) return;
  auto a = anchors_.find(it->second.key);
  if (a != anchors_.end()) a->second.anchor.prepare_for_new();
  in_flight_[tag] = it->second;
  pending_.erase(it);
}

template <int Dim>
void ShGraphCore<Dim>::refused(std::uint64_t tag) {
  pending_.erase(tag);
}

// The members defined here, for both dimensions: the class template is declared extern in
// the header, and each concern's file instantiates its own members.
template void ShGraphCore<2>::update_working_depth(const FrameContext&);
template std::vector<CaptureRequest> ShGraphCore<2>::plan(const FrameContext&);
template void ShGraphCore<2>::started(std::uint64_t);
template void ShGraphCore<2>::refused(std::uint64_t);
template void ShGraphCore<3>::update_working_depth(const FrameContext&);
template std::vector<CaptureRequest> ShGraphCore<3>::plan(const FrameContext&);
template void ShGraphCore<3>::started(std::uint64_t);
template void ShGraphCore<3>::refused(std::uint64_t);

}  // namespace ambisim
