// SHGraph's anchors: acquiring and releasing them with their cells, delivering a finished
// capture (fading from what lookups showed there, D8), and the per-frame update (lifetimes,
// renewal, pruning, root shrink).
#include "policies/thesis/shgraph_core.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <vector>

namespace ambisim {

template <int Dim>
AnchorEntry* ShGraphCore<Dim>::share_existing(const Key& key) {
  auto it = anchors_.find(key);
  if (it == anchors_.end()) return nullptr;
  ++it->second.refs;
  return &it->second;
}

template <int Dim>
AnchorEntry& ShGraphCore<Dim>::materialize(std::int32_t i) {
  if (nodes_[i].anchor != nullptr) return *nodes_[i].anchor;
  const Key key = nodes_[i].key;
  auto [it, inserted] = anchors_.try_emplace(key);
  AnchorEntry& e = it->second;  // inserted: by the invariant no node of the chain had one
  const glm::dvec3 position = anchor_position(key);
  const glm::dvec3 capture = capture_position(position);  // moves only vertically
  e.position_z = position.z;
  e.capture_z = capture.z;
  // Its light is attributed where it was captured, never at the nominal point inside a solid
  // (L318). The sheet weighs horizontal distances only, and moves sets only vertically.
  if constexpr (Dim == 3) e.capture_qz = (capture.z - origin_.z) / h_;
  // Every node of the chain: up while the node is its parent's centre child, then down.
  std::int32_t top = i;
  while (nodes_[top].parent >= 0 && nodes_[nodes_[top].parent].first_child + kCentreChild == top) {
    top = nodes_[top].parent;
  }
  for (std::int32_t m = top; m >= 0;
       m = nodes_[m].first_child >= 0 ? nodes_[m].first_child + kCentreChild : -1) {
    nodes_[m].anchor = &e;
    ++e.refs;
  }
  return e;
}

template <int Dim>
void ShGraphCore<Dim>::release_key(std::int32_t i) {
  Node& n = nodes_[i];
  if (n.anchor != nullptr) {
    if (--n.anchor->refs == 0) {
      forget(n.anchor);
      anchors_.erase(n.key);
    }
    n.anchor = nullptr;
    return;
  }
  // No anchor: the chain was never considered. The last node of a chain is the one that is not
  // its (live) parent's centre child, as above; the fill memo counts it as before.
  const std::int32_t p = n.parent;
  if (p < 0 || nodes_[p].first_child + kCentreChild != i) ++forgotten_;
}

template <int Dim>
void ShGraphCore<Dim>::forget(AnchorEntry* e) {
  ++forgotten_;
  if (e->anchor.has_coefficients()) by_age_.erase({e->anchor.creation_time(), e});
  if (e->anchor.fading()) std::erase(fading_, e);
}

template <int Dim>
void ShGraphCore<Dim>::set_coefficients(AnchorEntry* e, const Sh9Rgb& sh,
                                        const FinishedProbe& probe, const Sh9Rgb* fade_from,
                                        double fade_from_time) {
  CoefficientAnchor& a = e->anchor;
  if (a.has_coefficients()) {
    by_age_.erase({a.creation_time(), e});
  } else {
    e->entered_at = now_;  // a new set in the pattern (a replacement keeps its weight)
  }
  if (!a.fading()) fading_.push_back(e);
  a.set_new(sh, probe.requested_time, probe.tag, fade_from, fade_from_time);
  by_age_.insert({a.creation_time(), e});
}

template <int Dim>
void ShGraphCore<Dim>::deliver(const FinishedProbe& probe) {
  auto it = in_flight_.find(probe.tag);
  if (it == in_flight_.end()) return;
  const Key key = it->second.key;
  in_flight_.erase(it);
  auto a = anchors_.find(key);
  if (a == anchors_.end()) return;  // its branch was removed meanwhile
  CoefficientAnchor& anchor = a->second.anchor;
  const Sh9Rgb sh = s_.format.store(probe.sh);
  if (!anchor.has_coefficients() && s_.fade_from_lookup && s_.timing.fade_s > 0.0) {
    // D8: fade from what a lookup showed here just before, so the new set does not pop.
    const LookupResult before = lookup(anchor_point(key, a->second.position_z));
    if (before.contributor_count > 0) {
      set_coefficients(&a->second, sh, probe, &before.sh, before.data_time);
      return;
    }
  }
  set_coefficients(&a->second, sh, probe, nullptr, 0.0);
}

template <int Dim>
bool ShGraphCore<Dim>::protected_node(std::int32_t i, const Focus& focus) const {
  glm::dvec3 c = node_centre(i);
  Focus f = focus;
  if constexpr (Dim == 2) {
    c.z = 0.0;
    f.now.z = f.ahead.z = 0.0;
  }
  // Children of cells next to the focus are about to be wanted again: keep them.
  return f.distance(c) < 2.0 * cell_size(nodes_[i].depth);
}

template <int Dim>
std::uint32_t ShGraphCore<Dim>::refresh_masks(std::int32_t i, const Focus& focus, bool* in_flight) {
  std::uint32_t mask = 0;
  bool flight = false;
  bool own_data = false;  // data in a child other than through the shared centre anchor
  const std::int32_t fc = nodes_[i].first_child;
  if (fc >= 0) {
    for (int c = 0; c < kChildren; ++c) {
      bool cf = false;
      std::uint32_t m = 0;
      if (naive_ || nodes_[fc + c].first_child >= 0) {
        m = refresh_masks(fc + c, focus, &cf);
      } else {
        nodes_[fc + c].children_with_coefficients = 0;  // a leaf: what the call would do
      }
      const AnchorEntry* e = nodes_[fc + c].anchor;
      const bool has = e != nullptr && e->anchor.has_coefficients();
      if (has || m != 0) mask |= 1u << c;
      if (m != 0 || (has && c != kCentreChild)) own_data = true;
      flight = flight || cf || (e != nullptr && e->anchor.in_flight());
    }
    // Prune: no child holds coefficients of its own (the centre's are the parent's, which
    // keeps them), nothing is being captured below, and the camera is not about to need it.
    if (!own_data && !flight && !protected_node(i, focus)) {
      collapse(i);
      mask = 0;
    }
  }
  nodes_[i].children_with_coefficients = mask;
  *in_flight = flight;
  return mask;
}

template <int Dim>
void ShGraphCore<Dim>::update(const FrameContext& ctx) {
  world_ = ctx.world;
  now_ = ctx.time;
  clock_.advance(ctx);
  AnchorTiming timing = s_.timing;
  const double latency = ctx.capture_latency_s();
  timing.margin_s = 2.0 * (std::isfinite(latency) ? latency : 0.0) + 1.0;  // D7
  if (clock_.running()) {
    // Under changing light renewals go by clock age (the margin, real seconds, in clock seconds
    // at its speed now; a clock age is never below the real age, so the anchors visited below
    // include every one that can expire); under still light the clock is real time.
    timing.clock = &clock_;
    timing.margin_s *= clock_.speed();
  }
  const auto age_of = [&](double t) { return clock_.running() ? clock_.age(t) : now_ - t; };
  // Every anchor's update(), visiting only those it can change: anchors mid-fade, and anchors
  // whose set is old enough to expire or to ask for renewal now. For any other anchor with a
  // set, age <= lifetime - max(margin now, margin before) - 1 s: not expired, and its renewal
  // flag is false now and was false after the previous update (its age was smaller then), so
  // update() would leave it as it is. Anchors without a set and not fading: update() is a no-op.
  // The anchors are independent, so the order of the visits does not matter.
  if (naive_) {
    for (auto& [key, e] : anchors_) e.anchor.update(now_, timing);
    for (auto it = by_age_.begin(); it != by_age_.end();) {
      it = it->second->anchor.has_coefficients() ? std::next(it) : by_age_.erase(it);
    }
  } else {
    for (AnchorEntry* e : fading_) e->anchor.update(now_, timing);
    std::vector<AnchorEntry*> faded = fading_;
    std::sort(faded.begin(), faded.end());
    const double renew_age = s_.timing.lifetime_s - std::max(timing.margin_s, margin_prev_s_) - 1.0;
    for (auto it = by_age_.begin(); it != by_age_.end() && age_of(it->first) > renew_age;) {
      AnchorEntry* e = it->second;
      if (!std::binary_search(faded.begin(), faded.end(), e)) e->anchor.update(now_, timing);
      it = e->anchor.has_coefficients() ? std::next(it) : by_age_.erase(it);
    }
  }
  margin_prev_s_ = timing.margin_s;
  std::erase_if(fading_, [](const AnchorEntry* e) { return !e->anchor.fading(); });
  // A capture that never came back (budget gone) must not block its anchor for ever.
  for (auto it = in_flight_.begin(); it != in_flight_.end();) {
    if (now_ - it->second.requested_time > s_.timing.lifetime_s) {
      auto a = anchors_.find(it->second.key);
      if (a != anchors_.end()) a->second.anchor.cancel_request();
      it = in_flight_.erase(it);
    } else {
      ++it;
    }
  }
  if (nodes_.empty()) return;
  const Focus focus = make_focus(ctx, s_.prediction);
  bool flight = false;
  refresh_masks(0, focus, &flight);
  // D9 shrink: a grown root goes once at most one child holds coefficients (for
  // shrink_hold_s), keeping that child, provided the camera is in it (else it would regrow).
  while (nodes_[0].depth < 0 && nodes_[0].first_child >= 0) {
    const std::uint32_t mask = nodes_[0].children_with_coefficients;
    const int child = child_containing(0, to_q(focus.now));
    if (std::popcount(mask) > 1 || (mask != 0 && mask != (1u << child)) ||
        !contains(0, to_q(focus.now))) {
      shrink_since_ = -1.0;
      break;
    }
    if (shrink_since_ < 0.0) shrink_since_ = now_;
    if (now_ - shrink_since_ < s_.shrink_hold_s) break;
    shrink_root(child);
  }
}

// The members defined here, for both dimensions: the class template is declared extern in
// the header, and each concern's file instantiates its own members.
template AnchorEntry* ShGraphCore<2>::share_existing(const Key&);
template AnchorEntry& ShGraphCore<2>::materialize(std::int32_t);
template void ShGraphCore<2>::release_key(std::int32_t);
template void ShGraphCore<2>::forget(AnchorEntry*);
template void ShGraphCore<2>::set_coefficients(AnchorEntry*, const Sh9Rgb&, const FinishedProbe&,
                                               const Sh9Rgb*, double);
template void ShGraphCore<2>::deliver(const FinishedProbe&);
template bool ShGraphCore<2>::protected_node(std::int32_t, const Focus&) const;
template std::uint32_t ShGraphCore<2>::refresh_masks(std::int32_t, const Focus&, bool*);
template void ShGraphCore<2>::update(const FrameContext&);
template AnchorEntry* ShGraphCore<3>::share_existing(const Key&);
template AnchorEntry& ShGraphCore<3>::materialize(std::int32_t);
template void ShGraphCore<3>::release_key(std::int32_t);
template void ShGraphCore<3>::forget(AnchorEntry*);
template void ShGraphCore<3>::set_coefficients(AnchorEntry*, const Sh9Rgb&, const FinishedProbe&,
                                               const Sh9Rgb*, double);
template void ShGraphCore<3>::deliver(const FinishedProbe&);
template bool ShGraphCore<3>::protected_node(std::int32_t, const Focus&) const;
template std::uint32_t ShGraphCore<3>::refresh_masks(std::int32_t, const Focus&, bool*);
template void ShGraphCore<3>::update(const FrameContext&);

}  // namespace ambisim
