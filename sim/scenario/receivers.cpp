// Receivers JSON ("receivers" object). Units: metres, seconds, m/s. Defaults in brackets.
//   seed            non-negative integer                                                 [1]
//   camera_object   {"enabled" [true], "ahead_m" [8] along the camera's horizontal heading
//                    (-1e4..1e4), "follow" "ground" | "camera" ["ground"], "height_m" [1]
//                    above the ground (0..1e4) or above the camera (-1e4..1e4)}
//   lod_props       absent = none; {"trigger": [x, y, z] required (x, y used),
//                    "lod_distance_m" > 0 [200], "rate_per_s" >= 0 [50],
//                    "band_near_m" >= 0 [20], "band_far_m" >= near [150],
//                    "band_half_width_m" >= 0 [40], "min_height_m" >= 0 [0.5],
//                    "max_height_m" >= min [2], "lifetime_s" > 0 [30],
//                    "behind_margin_m" >= 0 [10], "max_live" 0..10000 [1000]}; a prop's
//                    size (diameter seen) is its height above the ground
//   traffic         absent = none; needs the world's road; {"rate_per_s" 0..1e4 [10],
//                    "speed_mps" 0..1000 [30], "speed_spread" 0..0.9 [0],
//                    "window_behind_m" >= 0 [200], "window_ahead_m" >= 0 [800],
//                    "lane_offset_m" [road_width / 4], "height_m" >= 0 [1],
//                    "max_live" 0..10000 [500], "size_m" (0, 1e3] [2]}
//   crowd           absent = none; {"centre": [x, y, z] or a landmark required (x, y used),
//                    "count" 0..10000 [2000], "radius_m" > 0 [150], "walking_share" 0..1
//                    [0.5], "speed_mps" 0..10 [1.4], "wander_m" >= 0 [8], "height_m" >= 0
//                    [1], "size_m" (0, 1e3] [1]}
//   recorded        absent = none; {"file" required: CSV tracks id,time,x,y,z[,vx,vy,vz]
//                    relative to the scenario file (recorded_track.h; at most 10000 alive at
//                    once), "size_m" (0, 1e3] [2]}
#include "sim/scenario/receivers.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "sim/base/hash.h"

namespace ambisim {
namespace {

// Every live receiver gets a reference capture on every frame: beyond this many a run would
// never finish (and its reference would not fit in memory).
constexpr int kMaxLive = 10000;
constexpr double kMaxOffset = 1e4;         // m: camera object placement
const Range kSize{0.0, 1e3, true, false};  // m: a receiver's diameter
// Spawn counts are floor(active seconds x rate); this absorbs float error in the product so
// that 10 s at 50/s is 500, not 499.
constexpr double kCountSnap = 1e-9;
// Hash streams, one per spawner, so adding a spawner never changes another's draws.
constexpr std::uint64_t kLodStream = 0x4C4F4450524F5053ull;
constexpr std::uint64_t kTrafficStream = 0x5452414646494331ull;
constexpr std::uint64_t kCrowdStream = 0x43524f5744303031ull;

int kind_index(ReceiverKind k) { return static_cast<int>(k); }

glm::dvec3 horizontal(const glm::dvec3& v) { return {v.x, v.y, 0.0}; }

std::int64_t due(double active_s, double rate) {
  return static_cast<std::int64_t>(std::floor(active_s * rate + kCountSnap));
}

}  // namespace

const char* receiver_kind_name(ReceiverKind kind) {
  switch (kind) {
    case ReceiverKind::camera_object:
      return "camera_object";
    case ReceiverKind::lod_prop:
      return "lod_prop";
    case ReceiverKind::traffic:
      return "traffic";
    case ReceiverKind::recorded:
      return "recorded";
    case ReceiverKind::crowd:
      return "crowd";
  }
  return "?";
}

ReceiversRecord parse_receivers(ObjectReader& r) {
  ReceiversRecord rec;
  rec.seed = r.seed("seed", 1);
  if (auto c = r.optional_object("camera_object")) {
    rec.camera_object.enabled = c->boolean("enabled", true);
    rec.camera_object.ahead_m = c->number("ahead_m", 8.0, Range::closed(-kMaxOffset, kMaxOffset));
    const bool camera = c->choice("follow", "ground", {"ground", "camera"}) == "camera";
    rec.camera_object.follow =
        camera ? CameraObjectRecord::Follow::camera : CameraObjectRecord::Follow::ground;
    rec.camera_object.height_m =
        c->number("height_m", 1.0, Range::closed(camera ? -kMaxOffset : 0.0, kMaxOffset));
    rec.camera_object.size_m = c->number("size_m", rec.camera_object.size_m, kSize);
    c->finish();
  }
  if (auto p = r.optional_object("lod_props")) {
    LodPropsRecord l;
    l.trigger = read_position(*p, "trigger", kMaxScenarioCoord, l.trigger_landmark, 0);
    l.lod_distance_m = p->number("lod_distance_m", l.lod_distance_m, Range::positive());
    l.rate_per_s = p->number("rate_per_s", l.rate_per_s, Range::closed(0.0, 1e4));
    l.band_near_m = p->number("band_near_m", l.band_near_m, Range::non_negative());
    l.band_far_m = p->number("band_far_m", l.band_far_m, Range::non_negative());
    if (l.band_far_m < l.band_near_m) p->fail("band_far_m", "must be >= band_near_m");
    l.band_half_width_m =
        p->number("band_half_width_m", l.band_half_width_m, Range::non_negative());
    l.min_height_m = p->number("min_height_m", l.min_height_m, Range::non_negative());
    l.max_height_m = p->number("max_height_m", l.max_height_m, Range::non_negative());
    if (l.max_height_m < l.min_height_m) p->fail("max_height_m", "must be >= min_height_m");
    l.lifetime_s = p->number("lifetime_s", l.lifetime_s, Range::positive());
    l.behind_margin_m = p->number("behind_margin_m", l.behind_margin_m, Range::non_negative());
    l.max_live = p->integer("max_live", l.max_live, Range::closed(0, kMaxLive));
    p->finish();
    rec.lod_props = l;
  }
  if (auto t = r.optional_object("traffic")) {
    TrafficRecord tr;
    tr.rate_per_s = t->number("rate_per_s", tr.rate_per_s, Range::closed(0.0, 1e4));
    tr.speed_mps = t->number("speed_mps", tr.speed_mps, Range::closed(0.0, 1e3));
    tr.speed_spread = t->number("speed_spread", tr.speed_spread, Range::closed(0.0, 0.9));
    tr.window_behind_m = t->number("window_behind_m", tr.window_behind_m, Range::non_negative());
    tr.window_ahead_m = t->number("window_ahead_m", tr.window_ahead_m, Range::non_negative());
    if (t->has("lane_offset_m")) {
      tr.lane_offset_m = t->number("lane_offset_m", Range::closed(-1e3, 1e3));
    }
    tr.height_m = t->number("height_m", tr.height_m, Range::non_negative());
    tr.max_live = t->integer("max_live", tr.max_live, Range::closed(0, kMaxLive));
    tr.size_m = t->number("size_m", tr.size_m, kSize);
    t->finish();
    rec.traffic = tr;
  }
  if (auto c = r.optional_object("crowd")) {
    CrowdRecord cr;
    cr.centre = read_position(*c, "centre", kMaxScenarioCoord, cr.centre_landmark, 0);
    cr.count = c->integer("count", cr.count, Range::closed(0, kMaxLive));
    cr.radius_m = c->number("radius_m", cr.radius_m, Range::positive());
    cr.walking_share = c->number("walking_share", cr.walking_share, Range::closed(0.0, 1.0));
    cr.speed_mps = c->number("speed_mps", cr.speed_mps, Range::closed(0.0, 10.0));
    cr.wander_m = c->number("wander_m", cr.wander_m, Range::non_negative());
    cr.height_m = c->number("height_m", cr.height_m, Range::non_negative());
    cr.size_m = c->number("size_m", cr.size_m, kSize);
    c->finish();
    rec.crowd = cr;
  }
  if (auto c = r.optional_object("recorded")) {
    RecordedReceiversRecord rr;
    rr.tracks = read_recorded_receivers(*c, "file", kMaxLive);
    rr.size_m = c->number("size_m", rr.size_m, kSize);
    c->finish();
    rec.recorded = rr;
  }
  r.finish();
  return rec;
}

void resolve_receiver_landmarks(ReceiversRecord& record, const WorldLandmarks& landmarks,
                                const std::string& file) {
  if (record.crowd) {
    for (const auto& ref : record.crowd->centre_landmark) {
      record.crowd->centre = resolve_landmark(ref, landmarks, file);
    }
    record.crowd->centre_landmark.clear();
  }
  if (!record.lod_props) return;
  for (const auto& ref : record.lod_props->trigger_landmark) {
    record.lod_props->trigger = resolve_landmark(ref, landmarks, file);
  }
  record.lod_props->trigger_landmark.clear();
}

ReceiverSet::ReceiverSet(const ReceiversRecord& record, const TerrainQueries& terrain)
    : rec_(record), terrain_(terrain) {
  if ((rec_.camera_object.enabled || rec_.lod_props || rec_.crowd) && !terrain_.ground_height) {
    throw std::invalid_argument("receivers need ground height");
  }
  if (rec_.traffic) {
    if (terrain_.road == nullptr || terrain_.road->empty()) {
      throw std::invalid_argument("traffic needs a road");
    }
    lane_offset_ = rec_.traffic->lane_offset_m.value_or(0.25 * terrain_.road_width);
  }
  if (rec_.recorded && !rec_.recorded->tracks) {
    throw std::invalid_argument("recorded receivers need their tracks");
  }
}

double ReceiverSet::uniform(std::uint64_t stream, std::int64_t index, int component) const {
  return hash_unit(hash_combine(rec_.seed, stream), index, component);
}

Receiver& ReceiverSet::spawn(ReceiverKind kind, double time) {
  Receiver r;
  r.id = kind == ReceiverKind::camera_object ? 0 : next_id_++;
  r.kind = kind;
  r.spawn_time = time;
  r.despawn_time = std::numeric_limits<double>::infinity();
  r.kind_order = counters_.spawned[kind_index(kind)];
  live_.push_back(r);  // ids only grow, so appending keeps id order
  ++counters_.spawned[kind_index(kind)];
  return live_.back();
}

std::int64_t ReceiverSet::live_count(ReceiverKind kind) const {
  return std::count_if(live_.begin(), live_.end(),
                       [kind](const Receiver& r) { return r.kind == kind; });
}

void ReceiverSet::update(double time, const CameraState& camera) {
  if (!started_) {
    started_ = true;
    start_time_ = time;
    last_time_ = time;
  }
  gone_.clear();
  const glm::dvec3 v = horizontal(camera.velocity);
  if (glm::length(v) > 1e-9) heading_ = glm::normalize(v);
  if (rec_.camera_object.enabled) update_camera_object(time, camera);
  if (rec_.lod_props) update_lod_props(time, camera);
  if (rec_.traffic) update_traffic(time, camera);
  if (rec_.recorded) update_recorded(time);
  if (rec_.crowd) update_crowd(time);
  last_time_ = time;
}

double ReceiverSet::stand_height(double x, double y) const {
  return terrain_.surface_height ? terrain_.surface_height(x, y) : terrain_.ground_height(x, y);
}

void ReceiverSet::update_camera_object(double time, const CameraState& camera) {
  if (live_.empty() || live_.front().id != 0) {
    spawn(ReceiverKind::camera_object, time);
    std::rotate(live_.begin(), live_.end() - 1, live_.end());  // id 0 goes first
  }
  Receiver& r = live_.front();
  const glm::dvec3 p = horizontal(camera.position) + rec_.camera_object.ahead_m * heading_;
  // Objects stand on whatever is solid: in a forest that is the canopy top (the world has no
  // space under the trees; a point inside the canopy would be inside a solid column).
  const double ground = stand_height(p.x, p.y);
  const glm::dvec3 vh = horizontal(camera.velocity);
  if (rec_.camera_object.follow == CameraObjectRecord::Follow::camera) {
    const double flying = camera.position.z + rec_.camera_object.height_m;
    const double lowest = ground + CameraObjectRecord::kMinClearance;
    r.position = {p.x, p.y, std::max(flying, lowest)};
    r.velocity = {vh.x, vh.y, flying >= lowest ? camera.velocity.z : 0.0};
    r.size_m = rec_.camera_object.size_m;
    return;
  }
  r.position = {p.x, p.y, ground + rec_.camera_object.height_m};
  r.size_m = rec_.camera_object.size_m;
  // Vertical speed follows the ground slope along the heading (central difference, +-0.5 m).
  const glm::dvec3 a = p - 0.5 * heading_;
  const glm::dvec3 b = p + 0.5 * heading_;
  const double slope = stand_height(b.x, b.y) - stand_height(a.x, a.y);
  r.velocity = {vh.x, vh.y, slope * glm::dot(vh, heading_)};
}

void ReceiverSet::update_lod_props(double time, const CameraState& camera) {
  const LodPropsRecord& L = *rec_.lod_props;
  const glm::dvec3 cam = horizontal(camera.position);
  // Despawn: lifetime over, or left behind the camera.
  auto expired = [&](const Receiver& r) {
    if (r.kind != ReceiverKind::lod_prop) return false;
    return time >= r.despawn_time ||
           glm::dot(horizontal(r.position) - cam, heading_) < -L.behind_margin_m;
  };
  for (auto& r : live_) {
    if (expired(r)) {
      gone_.push_back(r);
      gone_.back().despawn_time = time;
      ++counters_.despawned[kind_index(ReceiverKind::lod_prop)];
    }
  }
  live_.erase(std::remove_if(live_.begin(), live_.end(), expired), live_.end());

  // Spawn clock: runs while the camera is within lod distance of the trigger.
  const bool inside = glm::length(cam - horizontal(L.trigger)) <= L.lod_distance_m;
  if (inside && !lod_inside_) lod_entered_ = time;
  if (!inside && lod_inside_) lod_base_ += last_time_ - lod_entered_;
  lod_inside_ = inside;
  if (!inside) return;
  const std::int64_t target = due(lod_base_ + (time - lod_entered_), L.rate_per_s);
  std::int64_t live_props = live_count(ReceiverKind::lod_prop);
  const glm::dvec3 right = right_of(heading_);
  for (; lod_emitted_ < target; ++lod_emitted_) {
    if (live_props >= L.max_live) {
      ++counters_.suppressed[kind_index(ReceiverKind::lod_prop)];
      continue;
    }
    const std::int64_t n = lod_emitted_;
    const double d = L.band_near_m + uniform(kLodStream, n, 0) * (L.band_far_m - L.band_near_m);
    const double w = (2.0 * uniform(kLodStream, n, 1) - 1.0) * L.band_half_width_m;
    const glm::dvec3 p = cam + d * heading_ + w * right;
    const double h = L.min_height_m + uniform(kLodStream, n, 2) * (L.max_height_m - L.min_height_m);
    Receiver& r = spawn(ReceiverKind::lod_prop, time);
    r.position = {p.x, p.y, stand_height(p.x, p.y) + h};
    r.velocity = glm::dvec3(0.0);
    r.size_m = h;
    r.despawn_time = time + L.lifetime_s;
    ++live_props;
  }
}

void ReceiverSet::update_traffic(double time, const CameraState& camera) {
  const TrafficRecord& T = *rec_.traffic;
  const Spline3& road = *terrain_.road;
  // The window follows the camera's road position and its direction of travel on the road.
  const double s_cam = road.closest_s(camera.position);
  const double along = glm::dot(camera.velocity, road.tangent(s_cam));
  if (std::abs(along) > 1e-9) camera_road_dir_ = along > 0.0 ? 1 : -1;
  const double e1 = s_cam - camera_road_dir_ * T.window_behind_m;
  const double e2 = s_cam + camera_road_dir_ * T.window_ahead_m;
  const double lo = std::max(std::min(e1, e2), 0.0);
  const double hi = std::min(std::max(e1, e2), road.length());

  auto s_of = [&](const Receiver& r) {
    return r.road_s0 + r.lane_direction * r.road_speed * (time - r.spawn_time);
  };
  auto place = [&](Receiver& r) {
    const double s = s_of(r);
    r.position = lane_point(road, s, r.lane_direction, lane_offset_, T.height_m);
    r.velocity = (r.lane_direction * r.road_speed) *
                 lane_derivative(road, s, r.lane_direction, lane_offset_);
  };
  auto left = [&](const Receiver& r) {
    if (r.kind != ReceiverKind::traffic) return false;
    const double s = s_of(r);
    return s < lo || s > hi;
  };
  for (auto& r : live_) {
    if (left(r)) {
      gone_.push_back(r);
      gone_.back().despawn_time = time;
      ++counters_.despawned[kind_index(ReceiverKind::traffic)];
    } else if (r.kind == ReceiverKind::traffic) {
      place(r);
    }
  }
  live_.erase(std::remove_if(live_.begin(), live_.end(), left), live_.end());

  const std::int64_t target = due(time - start_time_, T.rate_per_s);
  std::int64_t live_cars = live_count(ReceiverKind::traffic);
  for (; traffic_emitted_ < target; ++traffic_emitted_) {
    if (live_cars >= T.max_live || !(hi > lo)) {
      ++counters_.suppressed[kind_index(ReceiverKind::traffic)];
      continue;
    }
    const std::int64_t n = traffic_emitted_;
    Receiver& r = spawn(ReceiverKind::traffic, time);
    r.road_s0 = lo + uniform(kTrafficStream, n, 0) * (hi - lo);
    r.lane_direction = uniform(kTrafficStream, n, 1) < 0.5 ? 1 : -1;
    r.road_speed =
        T.speed_mps * (1.0 + T.speed_spread * (2.0 * uniform(kTrafficStream, n, 2) - 1.0));
    r.size_m = T.size_m;
    place(r);
    ++live_cars;
  }
}

void ReceiverSet::update_recorded(double time) {
  const RecordedReceivers& R = *rec_.recorded->tracks;
  // Despawn after the last sample (alive through it), then move the others.
  auto over = [&](const Receiver& r) {
    return r.kind == ReceiverKind::recorded && time > R.tracks[r.track].last_time();
  };
  for (auto& r : live_) {
    if (over(r)) {
      gone_.push_back(r);
      gone_.back().despawn_time = time;
      ++counters_.despawned[kind_index(ReceiverKind::recorded)];
    }
  }
  live_.erase(std::remove_if(live_.begin(), live_.end(), over), live_.end());
  for (auto& r : live_) {
    if (r.kind != ReceiverKind::recorded) continue;
    const RecordedTrack::State s = R.tracks[r.track].at(time);
    r.position = s.position;
    r.velocity = s.velocity;
  }
  // Spawn in track order (by first sample time): every track whose first sample has come.
  for (; next_track_ < R.tracks.size() && R.tracks[next_track_].first_time() <= time;
       ++next_track_) {
    const RecordedTrack& track = R.tracks[next_track_];
    if (time > track.last_time()) {
      ++counters_.recorded_missed;  // its whole life fell between two frames
      continue;
    }
    Receiver& r = spawn(ReceiverKind::recorded, time);
    r.track = next_track_;
    r.size_m = rec_.recorded->size_m;
    r.despawn_time = track.last_time();
    const RecordedTrack::State s = track.at(time);
    r.position = s.position;
    r.velocity = s.velocity;
  }
}

void ReceiverSet::update_crowd(double time) {
  const CrowdRecord& C = *rec_.crowd;
  constexpr double kTwoPi = 6.28318530717958647692;
  // Member i: home uniform in the disc (u0, u1), walking if u2 < walking_share, loop phases
  // (u3, u4) and frequencies from u5: x = A sin(w t + a), y = A sin(1.6 w t + b), whose speed
  // averages about speed_mps when A w = speed_mps / 1.4.
  auto place = [&](Receiver& r, std::int64_t i) {
    const double radius = C.radius_m * std::sqrt(uniform(kCrowdStream, i, 0));
    const double angle = kTwoPi * uniform(kCrowdStream, i, 1);
    glm::dvec3 p(C.centre.x + radius * std::cos(angle), C.centre.y + radius * std::sin(angle), 0.0);
    glm::dvec3 v(0.0);
    const bool walking = uniform(kCrowdStream, i, 2) < C.walking_share;
    if (walking && C.wander_m > 0.0 && C.speed_mps > 0.0) {
      const double w = C.speed_mps / (1.4 * C.wander_m) * (0.8 + 0.4 * uniform(kCrowdStream, i, 5));
      const double a = kTwoPi * uniform(kCrowdStream, i, 3),
                   b = kTwoPi * uniform(kCrowdStream, i, 4);
      const double t = time - start_time_;
      p.x += C.wander_m * std::sin(w * t + a);
      p.y += C.wander_m * std::sin(1.6 * w * t + b);
      v = {C.wander_m * w * std::cos(w * t + a), 1.6 * C.wander_m * w * std::cos(1.6 * w * t + b),
           0.0};
    }
    const double h = walking ? C.height_m : 0.5 + uniform(kCrowdStream, i, 6);
    p.z = stand_height(p.x, p.y) + h;
    r.position = p;
    r.velocity = v;  // horizontal: the slope's share is below a walker's notice
    r.size_m = C.size_m;
  };
  if (counters_.spawned[kind_index(ReceiverKind::crowd)] == 0) {
    for (int i = 0; i < C.count; ++i) spawn(ReceiverKind::crowd, time);
  }
  for (auto& r : live_) {
    if (r.kind == ReceiverKind::crowd) place(r, r.kind_order);
  }
}

}  // namespace ambisim
