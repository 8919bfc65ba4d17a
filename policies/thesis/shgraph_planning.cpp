// SHGraph's planning: the working depth from speed and frame rate (D2), and which cells to
// capture this frame: missing and expiring sets around the (predicted) camera, coarse to fine,
// then widened at the working depth.
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
    Node root;
    root.key.fill(pow3_[dmax_]);
    root.link.fill(-1);
    nodes_.push_back(root);
    nodes_[0].anchor = acquire(root.key);
  }
  const Q q_now = to_q(focus.now);
  const Q q_ahead = to_q(focus.ahead);
  while (!contains(0, q_now) && grow_towards(q_now)) {
  }
  while (!contains(0, q_ahead) && grow_towards(q_ahead)) {
  }

  struct Candidate {
    int tier;  // 0 missing near, 1 re-request near, 2 missing widened, 3 re-request widened
    int level;
    double score;  // distance to the focus, or capture time for re-requests (oldest first)
    Key key;
    glm::dvec3 capture;
    bool operator<(const Candidate& o) const {
      return std::tie(tier, level, score, key) < std::tie(o.tier, o.level, o.score, o.key);
    }
  };
  std::vector<Candidate> cands;
  std::set<Key> seen;
  const auto consider = [&](std::int32_t j, int near_tier, int level) {
    if (j < 0 || nodes_[j].depth != level) return;
    const AnchorEntry& e = *nodes_[j].anchor;
    if (e.anchor.in_flight() || !seen.insert(nodes_[j].key).second) return;
    glm::dvec3 c = e.position;
    if constexpr (Dim == 2) c.z = focus.now.z;  // horizontal distance on the sheet
    if (!e.anchor.has_coefficients()) {
      cands.push_back({near_tier, level, focus.distance(c), nodes_[j].key, e.capture});
    } else if (e.anchor.need_new()) {
      cands.push_back({near_tier + 1, 0, e.anchor.creation_time(), nodes_[j].key, e.capture});
    }
  };
  // Cells at `level` within Chebyshev radius r (exactly r when ring) of the focus segment.
  const auto region = [&](int level, int r, bool ring, int near_tier) {
    const double cell_q = 2.0 * static_cast<double>(half(level));
    double len = 0.0;
    for (int a = 0; a < Dim; ++a) len = std::max(len, std::abs(q_ahead[a] - q_now[a]));
    const int samples = 1 + static_cast<int>(std::ceil(len / cell_q));
    std::array<int, Dim> o{};
    const int side = 2 * r + 1;
    int cells = 1;
    for (int a = 0; a < Dim; ++a) cells *= side;
    for (int s = 0; s <= samples; ++s) {
      const double t = static_cast<double>(s) / samples;
      Q q;
      for (int a = 0; a < Dim; ++a) q[a] = q_now[a] + t * (q_ahead[a] - q_now[a]);
      const std::int32_t centre = ensure_node(q, level);
      if (centre < 0 || nodes_[centre].depth != level) continue;
      const Key ck = nodes_[centre].key;
      for (int n = 0; n < cells; ++n) {
        int rest = n, cheb = 0;
        for (int a = 0; a < Dim; ++a) {
          o[a] = rest % side - r;
          rest /= side;
          cheb = std::max(cheb, std::abs(o[a]));
        }
        if (ring && cheb != r) continue;
        Q p;
        for (int a = 0; a < Dim; ++a) p[a] = static_cast<double>(ck[a]) + o[a] * cell_q;
        if constexpr (Dim == 3) {
          if (s_.skip_underground && world_ != nullptr && world_->ground_height) {
            const double x = origin_.x + p[0] * h_, y = origin_.y + p[1] * h_;
            const double top = origin_.z + (p[2] + 0.5 * cell_q) * h_;
            if (top < world_->ground_height(x, y)) continue;  // the floor (L307)
          }
        }
        consider(ensure_node(p, level), near_tier, level);
      }
    }
  };
  const auto wanted = static_cast<std::size_t>(ctx.startable_captures);
  const int top = std::max(nodes_[0].depth, 0);
  // Coarse to fine, but only in the 3^Dim neighbourhood: sufficient resolution all around the
  // (predicted) camera at once, far nodes later (L566, L552).
  // At the normal root size and above only the focus cell itself: its neighbours are not part
  // of the normal graph, and capturing them would keep a grown root from ever shrinking (D9).
  for (int level = top; level <= d_eff_; ++level) region(level, level <= 0 ? 0 : 1, false, 0);
  // Then widen at the working depth (L420).
  for (int r = 2; d_eff_ > 0 && r <= s_.widen_cells && cands.size() < wanted; ++r) {
    region(d_eff_, r, true, 2);
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
