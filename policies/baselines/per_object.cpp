#include "policies/baselines/per_object.h"

#include <algorithm>
#include <limits>

#include <glm/geometric.hpp>

#include "policies/core/container_bytes.h"
#include "policies/core/default_ambient.h"

namespace ambisim {

PlannerInfo PerObjectPlanner::info() {
  std::vector<ParamSpec> params = {
      number_param("move_m", 5.0, Range::positive(),
                   "re-capture once the object is this far from where its capture was taken"),
      number_param("lifetime_s", 10.0, Range::positive(),
                   "re-capture once the capture is this old (the light may have changed)")};
  for (auto& s : coefficient_format_params()) params.push_back(std::move(s));
  return {"per_object",
          "one capture per receiver, re-captured every move_m or lifetime_s (thesis 7.5.1)",
          std::move(params),
          [](const PlannerParams& p) { return std::make_unique<PerObjectPlanner>(p); }};
}

PerObjectPlanner::PerObjectPlanner(const PlannerParams& params)
    : params_(params),
      format_(coefficient_format_from(params)),
      move_m_(params.number("move_m")),
      lifetime_s_(params.number("lifetime_s")) {}

void PerObjectPlanner::set_receivers(const std::vector<ReceiverView>& receivers) {
  // The same receivers where they were (props that stand still): both maps already hold them.
  const bool same = receivers.size() == last_receivers_.size() &&
                    std::equal(receivers.begin(), receivers.end(), last_receivers_.begin(),
                               [](const ReceiverView& a, const Placed& b) {
                                 return a.id == b.id && a.position == b.position;
                               });
  if (same) return;
  last_receivers_.clear();
  for (const auto& r : receivers) last_receivers_.push_back({r.id, r.position});
  // Both maps are rebuilt from the receivers every frame, but from their own nodes: an object
  // keeps its node (and its capture), and the position index's nodes are reused, so a frame of
  // 1e3 receivers allocates nothing once their number is steady.
  std::map<std::uint64_t, Object> next;
  for (const auto& r : receivers) {
    auto it = next.find(r.id);
    if (it == next.end()) {
      auto node = objects_.extract(r.id);
      if (node.empty()) {
        it = next.emplace(r.id, Object{}).first;
      } else {
        it = next.insert(std::move(node)).position;
      }
    }
    it->second.position = r.position;
  }
  objects_ = std::move(next);  // despawned receivers are forgotten with their capture
  spare_positions_.clear();
  while (!by_position_.empty())
    spare_positions_.push_back(by_position_.extract(by_position_.begin()));
  for (const auto& r : receivers) {
    const Key key{r.position.x, r.position.y, r.position.z};
    if (spare_positions_.empty()) {
      by_position_.emplace(key, r.id);  // the first id at a position wins
      continue;
    }
    auto node = std::move(spare_positions_.back());
    spare_positions_.pop_back();
    node.key() = key;
    node.mapped() = r.id;
    auto done = by_position_.insert(std::move(node));
    if (!done.inserted) spare_positions_.push_back(std::move(done.node));
  }
  spare_positions_.clear();
}

double PerObjectPlanner::outdatedness(const Object& o) const {
  return std::max(glm::distance(o.position, o.capture_position) / move_m_,
                  (now_ - o.data_time) / lifetime_s_);
}

bool PerObjectPlanner::needs_capture(const Object& o) const {
  return !o.in_flight && (!o.has_capture || outdatedness(o) > 1.0);
}

std::size_t PerObjectPlanner::backlog() const {
  return static_cast<std::size_t>(std::count_if(
      objects_.begin(), objects_.end(), [&](const auto& kv) { return needs_capture(kv.second); }));
}

std::vector<CaptureRequest> PerObjectPlanner::plan(const FrameContext& ctx) {
  pending_.clear();  // anything neither started nor refused last frame never started
  now_ = ctx.time;
  if (ctx.startable_captures <= 0) return {};
  // (captured, -outdatedness, id): uncaptured first in spawn order, then the most outdated.
  struct Candidate {
    bool captured;
    double score;
    std::uint64_t id;
    bool operator<(const Candidate& o) const {
      if (captured != o.captured) return !captured;
      if (score != o.score) return score < o.score;
      return id < o.id;
    }
  };
  std::vector<Candidate> cands;
  for (const auto& [id, o] : objects_) {
    if (!needs_capture(o)) continue;
    cands.push_back({o.has_capture, o.has_capture ? -outdatedness(o) : 0.0, id});
  }
  const std::size_t n = std::min(cands.size(), static_cast<std::size_t>(ctx.startable_captures));
  std::partial_sort(cands.begin(), cands.begin() + static_cast<std::ptrdiff_t>(n), cands.end());
  std::vector<CaptureRequest> out;
  out.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint64_t tag = next_tag_++;
    pending_[tag] = cands[i].id;
    out.push_back({objects_.at(cands[i].id).position, tag});
  }
  return out;
}

void PerObjectPlanner::started(std::uint64_t tag) {
  auto it = pending_.find(tag);
  if (it == pending_.end()) return;
  if (auto o = objects_.find(it->second); o != objects_.end()) o->second.in_flight = true;
  in_flight_[tag] = it->second;
  pending_.erase(it);
}

void PerObjectPlanner::refused(std::uint64_t tag) { pending_.erase(tag); }

void PerObjectPlanner::deliver(const FinishedProbe& probe) {
  auto f = in_flight_.find(probe.tag);
  if (f == in_flight_.end()) return;
  const std::uint64_t id = f->second;
  in_flight_.erase(f);
  auto it = objects_.find(id);
  if (it == objects_.end()) return;  // despawned while its capture was rendered
  Object& o = it->second;
  o.in_flight = false;
  o.has_capture = true;
  o.capture_position = probe.position;
  o.sh = format_.store(probe.sh);
  o.data_time = probe.requested_time;
  o.tag = probe.tag;
}

void PerObjectPlanner::update(const FrameContext& ctx) { now_ = ctx.time; }

LookupResult PerObjectPlanner::lookup(const glm::dvec3& p) const {
  LookupResult r;
  const Object* best = nullptr;
  if (auto h = by_position_.find(Key{p.x, p.y, p.z}); h != by_position_.end()) {
    const Object& own = objects_.at(h->second);
    if (own.has_capture) best = &own;
  }
  if (best == nullptr) {
    double best_d = std::numeric_limits<double>::infinity();
    for (const auto& [id, o] : objects_) {  // ties: the lower id
      if (!o.has_capture) continue;
      const double d = glm::distance(o.position, p);
      if (d < best_d) {
        best_d = d;
        best = &o;
      }
    }
  }
  if (best == nullptr) return default_ambient_lookup();
  r.sh = best->sh;
  r.contributors[0] = {best->tag, 1.0f};
  r.contributor_count = 1;
  r.spacing_m = glm::distance(p, best->capture_position);
  r.data_time = best->data_time;
  return r;
}

PlannerStats PerObjectPlanner::stats() const {
  PlannerStats s;
  std::int64_t sets = 0;
  for (const auto& [id, o] : objects_) sets += o.has_capture ? 1 : 0;
  s.live_probes = sets;
  // Sets in their storage format (the Sh9Rgb inside Object is not counted twice); structure:
  // map nodes for objects, the position index and the capture tags, and the last receivers.
  const std::size_t object_node =
      sizeof(std::uint64_t) + sizeof(Object) - sizeof(Sh9Rgb) + kMapNodeOverhead;
  const std::size_t position_node = sizeof(Key) + sizeof(std::uint64_t) + kMapNodeOverhead;
  const std::size_t tag_node = 2 * sizeof(std::uint64_t) + kMapNodeOverhead;
  s.bytes = static_cast<std::int64_t>(
      static_cast<std::size_t>(sets) * format_.bytes_per_set() + objects_.size() * object_node +
      by_position_.size() * position_node + (pending_.size() + in_flight_.size()) * tag_node +
      last_receivers_.capacity() * sizeof(Placed));
  return s;
}

void PerObjectPlanner::describe_nodes(std::vector<ProbeNodeView>& out) const {
  for (const auto& [id, o] : objects_) {
    if (!o.has_capture && !o.in_flight) continue;
    ProbeNodeView v;
    v.centre = o.has_capture ? o.capture_position : o.position;
    v.has_data = o.has_capture;
    v.in_flight = o.in_flight;
    v.age_s = o.has_capture ? now_ - o.data_time : 0.0;
    if (o.has_capture) v.sh = o.sh;
    out.push_back(v);
  }
}

}  // namespace ambisim
