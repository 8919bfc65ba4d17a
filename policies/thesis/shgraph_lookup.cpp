// SHGraph's lookup (D4, D5: up to one set per octant from the deepest level that has any,
// weighted by distance), its statistics and the node views for viz.
#include "policies/thesis/shgraph_core.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>

#include "policies/core/container_bytes.h"
#include "policies/core/default_ambient.h"

namespace ambisim {

template <int Dim>
LookupResult ShGraphCore<Dim>::lookup(const glm::dvec3& p) const {
  LookupResult r;  // filled in place: one named result, so no copy on return
  bool found = false;
  if (!nodes_.empty()) {
    LookupPath path;
    path.q = to_q(p);
    path.outside = !contains(0, path.q);
    find_deepest(path.q, path.nodes, &path.count);
    found = lookup_into(path, r);
  }
  if (!found) r = default_ambient_lookup();
  return r;
}

template <int Dim>
bool ShGraphCore<Dim>::lookup_into(const LookupPath& lp, LookupResult& r, int above_depth) const {
  const Q& q = lp.q;
  const auto& path = lp.nodes;
  const int count = lp.count;

  constexpr int kOctants = 1 << Dim;
  struct Best {
    const AnchorEntry* e = nullptr;
    double d2 = std::numeric_limits<double>::infinity();
  };
  std::array<Best, kOctants> best{}, chosen{};
  int chosen_depth = 0;
  bool have = false;
  std::array<std::int32_t, kChildren> cells;  // every entry written by neighbourhood()
  for (int k = count - 1; k >= 0; --k) {
    const std::int32_t i = path[k];
    if (nodes_[i].depth >= above_depth) continue;
    best.fill(Best{});
    std::uint32_t covered = 0;
    // D5: the node and its 3^Dim - 1 same-depth neighbours, reached through the links.
    if (naive_) {
      neighbourhood_naive(i, cells);
    } else {
      neighbourhood(i, cells);
    }
    if (naive_) {
      for (int n = 0; n < kChildren; ++n) {
        const std::int32_t j = cells[static_cast<std::size_t>(n)];
        if (j < 0) continue;
        const AnchorEntry* e = nodes_[j].anchor;
        if (e == nullptr || !e->anchor.has_coefficients()) continue;
        const Q at = capture_q(nodes_[j].key, *e);
        double d2 = 0.0;
        int oct = 0;
        for (int a = 0; a < Dim; ++a) {
          const double dq = at[a] - q[a];
          d2 += dq * dq;
          if (dq >= 0.0) oct |= 1 << a;
        }
        covered |= 1u << oct;
        if (d2 < best[oct].d2) best[oct] = {e, d2};
      }
    } else {
      const Node* nodes = nodes_.data();
      for (std::size_t n = 0; n < static_cast<std::size_t>(kChildren); ++n) {
        const std::int32_t j = cells[n];
        if (j < 0) continue;
        const Node& nd = nodes[j];
        const AnchorEntry* e = nd.anchor;  // null: never considered, so no set
        if (e == nullptr || !e->anchor.has_coefficients()) continue;
        const Q at = capture_q(nd.key, *e);  // x and y from the node, in cache already
        double d2 = 0.0;
        int oct = 0;
        for (int a = 0; a < Dim; ++a) {
          const double dq = at[a] - q[a];
          d2 += dq * dq;
          oct |= (dq >= 0.0 ? 1 : 0) << a;
        }
        covered |= 1u << oct;
        Best& b = best[static_cast<std::size_t>(oct)];
        if (d2 < b.d2) b = {e, d2};
      }
    }
    if (covered == 0) continue;
    if (!have) {
      chosen = best;
      chosen_depth = nodes_[i].depth;
      have = true;
    }
    if (s_.level == LevelRule::first) break;
    if (covered == (1u << kOctants) - 1) {
      chosen = best;
      chosen_depth = nodes_[i].depth;
      break;
    }
  }
  if (!have) return false;
  const double cell = cell_size(chosen_depth);
  const double eps_q = 1e-3 * cell / h_;
  std::array<double, kOctants> w{};
  double sum = 0.0;
  for (int k = 0; k < kOctants; ++k) {
    if (!chosen[k].e) continue;
    const double d = std::sqrt(chosen[k].d2);
    if (d < eps_q) {  // an exact hit is that set alone (D4)
      w.fill(0.0);
      w[k] = 1.0;
      sum = 1.0;
      break;
    }
    if (s_.weights == WeightMode::compact) {
      w[k] = std::max(0.0, 1.0 - d * h_ / (2.0 * cell));
    } else {
      w[k] = 1.0 / d;
    }
    sum += w[k];
  }
  if (sum <= 0.0) {  // compact support left nothing: fall back to inverse distance
    for (int k = 0; k < kOctants; ++k) {
      if (chosen[k].e) sum += (w[k] = 1.0 / std::sqrt(chosen[k].d2));
    }
  }
  // 7.6's pattern blend. A set that appeared less than pattern_blend_s ago enters the weights
  // with its progress f (0 when it appeared, 1 after pattern_blend_s): the level answers
  // A = sum(w f sh) / sum(w f), mixed with the coarser levels' answer by the progress of its
  // most advanced set. A new set changes nothing the frame it appears (f = 0), and neither does
  // a level's first set (the mix is then all coarser answer, what the lookup gave before).
  std::array<double, kOctants> wn{};
  for (int k = 0; k < kOctants; ++k) wn[k] = chosen[k].e && w[k] > 0.0 ? w[k] / sum : 0.0;
  LookupResult coarse;
  double rest = 0.0;  // the coarser answer's weight
  if (s_.pattern_blend_s > 0.0) {
    std::array<double, kOctants> f{};
    double entered = 0.0, most = 0.0;
    for (int k = 0; k < kOctants; ++k) {
      if (!chosen[k].e) continue;  // an exact hit weighs one set, but the level has them all
      f[k] = std::clamp((now_ - chosen[k].e->entered_at) / s_.pattern_blend_s, 0.0, 1.0);
      entered += wn[k] * f[k];
      most = std::max(most, f[k]);
    }
    if (most < 1.0 && lookup_into(lp, coarse, chosen_depth)) rest = 1.0 - most;
    const double level_share = 1.0 - rest;
    if (entered < 1.0 - 1e-12 && entered > 0.0) {
      for (int k = 0; k < kOctants; ++k) wn[k] = wn[k] * f[k] / entered * level_share;
    } else if (entered <= 0.0 && rest > 0.0) {
      wn.fill(0.0);  // every set of the level just appeared: the coarser answer alone
      rest = 1.0;
    } else if (rest > 0.0) {
      for (int k = 0; k < kOctants; ++k) wn[k] *= level_share;
    }
  }
  double data_time = 0.0;
  // The fast path sums the 27 floats of each set as one flat array (vectorised): the same
  // products and sums, element by element, as the naive path's operators.
  static_assert(sizeof(Sh9Rgb) == kShCount * 3 * sizeof(float));
  std::array<float, kShCount * 3> acc{};
  for (int k = 0; k < kOctants; ++k) {
    if (!chosen[k].e || wn[k] <= 0.0) continue;
    const double wk = wn[k];
    const CoefficientAnchor& a = chosen[k].e->anchor;
    if (naive_) {
      r.sh += a.active() * static_cast<float>(wk);
    } else {
      const auto wf = static_cast<float>(wk);
      // Straight from the set's bytes (27 floats), no copy of it on the stack.
      const auto* bytes = reinterpret_cast<const unsigned char*>(&a.active());
      for (std::size_t c = 0; c < acc.size(); ++c) {
        float v;
        std::memcpy(&v, bytes + c * sizeof(float), sizeof v);
        acc[c] += v * wf;
      }
    }
    r.contributors[static_cast<std::size_t>(r.contributor_count++)] = {a.tag(),
                                                                       static_cast<float>(wk)};
    data_time += wk * a.data_time();
  }
  if (rest > 0.0) {
    const auto wf = static_cast<float>(rest);
    if (naive_) {
      r.sh += coarse.sh * wf;
    } else {
      for (std::size_t c = 0; c < r.sh.c.size(); ++c) {
        acc[3 * c] += coarse.sh.c[c].x * wf;
        acc[3 * c + 1] += coarse.sh.c[c].y * wf;
        acc[3 * c + 2] += coarse.sh.c[c].z * wf;
      }
    }
    data_time += rest * coarse.data_time;
    // The coarser sets join the contributors; beyond 8 the lightest give way.
    for (int c = 0; c < coarse.contributor_count; ++c) {
      auto con = coarse.contributors[static_cast<std::size_t>(c)];
      con.weight *= wf;
      if (r.contributor_count < 8) {
        r.contributors[static_cast<std::size_t>(r.contributor_count++)] = con;
        continue;
      }
      auto lightest =
          std::min_element(r.contributors.begin(), r.contributors.begin() + 8,
                           [](const auto& x, const auto& y) { return x.weight < y.weight; });
      if (lightest->weight < con.weight) *lightest = con;
    }
  }
  if (!naive_) {
    for (std::size_t c = 0; c < r.sh.c.size(); ++c) {
      r.sh.c[c] = Rgb(acc[3 * c], acc[3 * c + 1], acc[3 * c + 2]);
    }
  }
  r.data_time = data_time;
  r.spacing_m = cell;
  r.fell_back = lp.outside;  // outside the graph: the root's answer is only a coarse default
  return true;
}

template <int Dim>
PlannerStats ShGraphCore<Dim>::stats() const {
  PlannerStats s;
  if (naive_) {
    for (const auto& [key, e] : anchors_) s.live_probes += e.anchor.has_coefficients() ? 1 : 0;
  } else {
    s.live_probes = static_cast<std::int64_t>(by_age_.size());  // the anchors holding a set
  }
  s.nodes = static_cast<std::int64_t>(nodes_.size() - free_blocks_.size() * kChildren);
  // Sets: Active per anchor and New per fading anchor (a heap block), as the format stores
  // them. Structure: the anchor's bookkeeping (its struct minus the float set), the key and a
  // map node each; the node pool as allocated; the free list; the capture tag maps.
  const std::size_t per_anchor = s_.format.bytes_per_set() +
                                 (sizeof(AnchorEntry) - sizeof(Sh9Rgb)) + sizeof(Key) +
                                 kMapNodeOverhead;
  const std::size_t per_new = s_.format.bytes_per_set() + kHeapBlockOverhead;
  std::size_t news = 0;
  if (naive_) {
    for (const auto& [key, e] : anchors_) news += e.anchor.holds_new() ? 1 : 0;
  } else {
    for (const AnchorEntry* e : fading_) news += e->anchor.holds_new() ? 1 : 0;
  }
  const std::size_t per_tag =
      sizeof(typename std::map<std::uint64_t, InFlight>::value_type) + kMapNodeOverhead;
  s.bytes = static_cast<std::int64_t>(anchors_.size() * per_anchor + news * per_new +
                                      nodes_.capacity() * sizeof(Node) +
                                      free_blocks_.capacity() * sizeof(std::int32_t) +
                                      (pending_.size() + in_flight_.size()) * per_tag);
  return s;
}

template <int Dim>
void ShGraphCore<Dim>::describe_nodes(std::vector<ProbeNodeView>& out) const {
  if (nodes_.empty()) return;
  for (std::int32_t i = 0; i < static_cast<std::int32_t>(nodes_.size()); ++i) {
    if (!node_live(i)) continue;
    const Node& n = nodes_[i];
    ProbeNodeView v;
    v.centre = node_centre(i);
    const double hf = 0.5 * cell_size(n.depth);
    v.half_extent = glm::dvec3(hf, hf, Dim == 3 ? hf : 0.0);
    v.depth = n.depth - nodes_[0].depth;
    if (n.anchor != nullptr) {
      const CoefficientAnchor& a = n.anchor->anchor;
      v.has_data = a.has_coefficients();
      v.in_flight = a.in_flight();
      v.age_s = a.has_coefficients() ? now_ - a.creation_time() : 0.0;
      if (v.has_data) v.sh = a.active();
    }
    out.push_back(v);
  }
}

// The members defined here, for both dimensions: the class template is declared extern in
// the header, and each concern's file instantiates its own members.
template LookupResult ShGraphCore<2>::lookup(const glm::dvec3&) const;
template bool ShGraphCore<2>::lookup_into(const LookupPath&, LookupResult&, int) const;
template PlannerStats ShGraphCore<2>::stats() const;
template void ShGraphCore<2>::describe_nodes(std::vector<ProbeNodeView>&) const;
template LookupResult ShGraphCore<3>::lookup(const glm::dvec3&) const;
template bool ShGraphCore<3>::lookup_into(const LookupPath&, LookupResult&, int) const;
template PlannerStats ShGraphCore<3>::stats() const;
template void ShGraphCore<3>::describe_nodes(std::vector<ProbeNodeView>&) const;

}  // namespace ambisim
