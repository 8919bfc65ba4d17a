// Camera path JSON ("camera" object). Units: metres, seconds, m/s. Defaults in brackets.
//   type            "keyframes" | "road" | "recorded"                           ["keyframes"]
//   keyframes only:
//     points        [[x, y, z], ...], >= 2 distinct points, |coordinates| <= 1e10; the spline
//                   passes through them
//     z_mode        "absolute" | "above_ground": z is height above the ground at (x, y),
//                   applied at the points only (the spline between them may dip) ["absolute"]
//   road only:
//     lane_offset_m metres right of the centre line, in the direction of travel
//                                                         [road_width / 4: middle of the lane]
//     height_m      above the road surface, 0..1e5                                      [1.5]
//     start_arc_length_m  road arc length where the camera starts, 0..road length
//                   (checked against the built world: check_scenario_world)             [0]
//     direction     +1 along increasing road arc length, -1 against                     [1]
//   recorded only:
//     file          CSV telemetry time,x,y,z[,cut][,vx,vy,vz] (recorded_track.h), relative to the
//                   scenario file; with it only "view" applies (no speed, at_end or cuts: the
//                   file has its own)
//   keyframes and road:
//   speed_mps | speed_profile   see speed_profile.h (exactly one is required)
//   at_end          "hold" (stop at the end) | "loop" (jump back to the start; a cut unless
//                   the course is closed)                                               ["hold"]
//   cuts            [{"time_s" > 0, and one of "to_arc_length_m" >= 0 | "to_position" [x,y,z]
//                    | "jump_ahead_m"}], strictly increasing times                      [none]
//   periodic_cut    {"every_s" 0.01..86400, "first_s" > 0 [every_s], and one of "jump_ahead_m" |
//                    "targets_m": [course coordinates, cycled]}; not together with cuts [none]
//   view            the player's view (view_weights.h): {"fov_deg" (0, 180) horizontal [70],
//                    "aspect" 0.1..10 [16/9], "look_at" a position [none: along the heading]}
// Every position ([x, y, z]: keyframe points, to_position, look_at) may name a landmark
// instead: {"landmark": NAME, "offset": [along, left, up]} (landmark_ref.h).
// Course coordinates (to_arc_length_m, targets_m) are metres along the course from where the
// path starts; they are clamped to the course.
#include "sim/scenario/camera_path.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

namespace ambisim {
namespace {

// A loop whose end lies within this of its start is closed: wrapping is not a teleport.
constexpr double kClosedGap = 1e-6;  // m
// Positions and course distances are bounded as every scenario coordinate (landmark_ref.h).
const Range kCoord = Range::closed(-kMaxScenarioCoord, kMaxScenarioCoord);
const Range kDistance = Range::closed(0.0, kMaxScenarioCoord);
constexpr double kMaxHeight = 1e5;  // m above the road
// Spline3 merges points closer than this; a path needs two points farther apart.
constexpr double kSamePoint = 1e-9;       // m
constexpr double kMinCutInterval = 0.01;  // s, periodic cuts

bool distinct_points(const std::vector<glm::dvec3>& points) {
  return std::any_of(points.begin(), points.end(), [&](const glm::dvec3& q) {
    return glm::length(q - points.front()) > kSamePoint;
  });
}

std::vector<glm::dvec3> parse_points(ObjectReader& r, const char* key,
                                     std::vector<LandmarkRef>& refs) {
  const nlohmann::json* v = r.raw(key);
  if (!v) r.fail(key, "required array of [x, y, z] points is missing");
  if (!v->is_array() || v->size() < 2) r.fail(key, "must be an array of at least 2 [x, y, z]");
  std::vector<glm::dvec3> out;
  for (std::size_t i = 0; i < v->size(); ++i) {
    const std::string path = r.path_of(key) + "/" + std::to_string(i);
    out.push_back(read_position((*v)[i], r.file(), path, kMaxScenarioCoord, refs, i));
  }
  // With landmarks the points are known only once the world is: checked in
  // resolve_camera_landmarks.
  if (refs.empty() && !distinct_points(out)) r.fail(key, "needs at least 2 distinct points");
  return out;
}

CutRecord parse_cut(ObjectReader& e, std::vector<LandmarkRef>& refs, std::size_t index) {
  CutRecord c;
  c.time_s = e.number("time_s", Range::positive());
  const int kinds =
      int(e.has("to_arc_length_m")) + int(e.has("to_position")) + int(e.has("jump_ahead_m"));
  if (kinds != 1)
    e.fail("time_s", "give exactly one of to_arc_length_m, to_position, jump_ahead_m");
  if (e.has("to_arc_length_m")) {
    c.kind = CutRecord::Kind::to_arc_length;
    c.metres = e.number("to_arc_length_m", kDistance);
  } else if (e.has("to_position")) {
    c.kind = CutRecord::Kind::to_position;
    c.position = read_position(e, "to_position", kMaxScenarioCoord, refs, index);
  } else {
    c.kind = CutRecord::Kind::jump_ahead;
    c.metres = e.number("jump_ahead_m", kCoord);
  }
  e.finish();
  return c;
}

PeriodicCutRecord parse_periodic(ObjectReader& p) {
  PeriodicCutRecord rec;
  // Every periodic cut is cached as an anchor: at most 86400 s / 0.01 s of them.
  rec.every_s = p.number("every_s", Range::closed(kMinCutInterval, 86400.0));
  rec.first_s = p.number("first_s", rec.every_s, Range::positive());
  if (p.has("jump_ahead_m") == p.has("targets_m")) {
    p.fail("every_s", "give exactly one of jump_ahead_m or targets_m");
  }
  if (p.has("jump_ahead_m")) {
    rec.jump_ahead_m = p.number("jump_ahead_m", kCoord);
  } else {
    rec.targets_m = p.numbers("targets_m", kDistance);
    if (rec.targets_m.empty()) p.fail("targets_m", "needs at least one target");
  }
  p.finish();
  return rec;
}

void parse_view(ObjectReader& r, CameraPathRecord& rec) {
  if (auto v = r.optional_object("view")) {
    rec.view.fov_deg = v->number("fov_deg", rec.view.fov_deg, {0.0, 180.0, true, true});
    rec.view.aspect = v->number("aspect", rec.view.aspect, Range::closed(0.1, 10.0));
    if (v->has("look_at")) {
      rec.look_at = read_position(*v, "look_at", kMaxScenarioCoord, rec.look_at_landmark, 0);
    }
    v->finish();
  }
}

}  // namespace

CameraPathRecord parse_camera_path(ObjectReader& r) {
  CameraPathRecord rec;
  const std::string type = r.choice("type", "keyframes", {"keyframes", "road", "recorded"});
  if (type == "recorded") {
    rec.type = CameraPathRecord::Type::recorded;
    rec.recorded = read_recorded_camera(r, "file");
    parse_view(r, rec);
    r.finish();
    return rec;
  }
  if (type == "keyframes") {
    rec.type = CameraPathRecord::Type::keyframes;
    rec.points = parse_points(r, "points", rec.point_landmarks);
    rec.z_above_ground =
        r.choice("z_mode", "absolute", {"absolute", "above_ground"}) == "above_ground";
    for (auto& ref : rec.point_landmarks) ref.z_is_height = rec.z_above_ground;
  } else {
    rec.type = CameraPathRecord::Type::road;
    if (r.has("lane_offset_m"))
      rec.lane_offset_m = r.number("lane_offset_m", Range::closed(-1e3, 1e3));
    rec.height_m = r.number("height_m", 1.5, Range::closed(0.0, kMaxHeight));
    rec.start_arc_length_m = r.number("start_arc_length_m", 0.0, kDistance);
    rec.direction = r.integer("direction", 1, Range::closed(-1, 1));
    if (rec.direction == 0) r.fail("direction", "must be +1 or -1");
  }
  rec.speed = parse_speed_profile(r);
  rec.at_end = r.choice("at_end", "hold", {"hold", "loop"}) == "loop"
                   ? CameraPathRecord::AtEnd::loop
                   : CameraPathRecord::AtEnd::hold;
  if (r.has("cuts") && r.has("periodic_cut")) {
    r.fail("periodic_cut", "use either cuts or periodic_cut, not both");
  }
  if (r.has("cuts")) {
    for (auto& e : r.objects("cuts")) {
      CutRecord c = parse_cut(e, rec.cut_landmarks, rec.cuts.size());
      if (!rec.cuts.empty() && !(c.time_s > rec.cuts.back().time_s)) {
        e.fail("time_s", "must be greater than the previous cut's");
      }
      rec.cuts.push_back(c);
    }
  }
  if (auto p = r.optional_object("periodic_cut")) rec.periodic = parse_periodic(*p);
  parse_view(r, rec);
  r.finish();
  return rec;
}

void resolve_camera_landmarks(CameraPathRecord& record, const WorldLandmarks& landmarks,
                              const std::string& file) {
  resolve_landmarks(record.point_landmarks, landmarks, file, record.points);
  for (const auto& ref : record.cut_landmarks) {
    record.cuts.at(ref.index).position = resolve_landmark(ref, landmarks, file);
  }
  for (const auto& ref : record.look_at_landmark) {
    record.look_at = resolve_landmark(ref, landmarks, file);
  }
  if (!record.point_landmarks.empty() && !distinct_points(record.points)) {
    throw InputError(file, record.point_landmarks.front().path,
                     "the points need at least 2 distinct positions in this world");
  }
  record.point_landmarks.clear();
  record.cut_landmarks.clear();
  record.look_at_landmark.clear();
}

CameraPath::CameraPath(const CameraPathRecord& record, const TerrainQueries& terrain)
    : type_(record.type),
      at_end_(record.at_end),
      speed_(record.speed),
      cuts_(record.cuts),
      periodic_(record.periodic) {
  if (type_ == CameraPathRecord::Type::recorded) {
    if (!record.recorded) throw std::invalid_argument("a recorded camera path needs its samples");
    recorded_ = record.recorded;
    anchors_.push_back({0.0, 0.0});
    anchors_complete_ = true;
    return;
  }
  if (type_ == CameraPathRecord::Type::keyframes) {
    std::vector<glm::dvec3> pts = record.points;
    if (record.z_above_ground) {
      if (!terrain.ground_height) throw std::invalid_argument("z_mode above_ground needs ground");
      for (auto& p : pts) p.z += terrain.ground_height(p.x, p.y);
    }
    spline_ = Spline3(std::move(pts));
    course_length_ = spline_.length();
  } else {
    if (terrain.road == nullptr || terrain.road->empty()) {
      throw std::invalid_argument("a road camera path needs a road");
    }
    road_ = terrain.road;
    lane_offset_ = record.lane_offset_m.value_or(0.25 * terrain.road_width);
    height_ = record.height_m;
    start_s_ = record.start_arc_length_m;
    direction_ = record.direction >= 0 ? 1 : -1;
    if (start_s_ > road_->length()) {
      throw std::invalid_argument("start_arc_length_m is beyond the end of the road");
    }
    course_length_ = direction_ > 0 ? road_->length() - start_s_ : start_s_;
  }
  const bool loop = at_end_ == CameraPathRecord::AtEnd::loop;
  if (loop && !(course_length_ > 0.0)) throw std::invalid_argument("cannot loop an empty course");
  closed_ = loop && glm::length(course_point(course_length_) - course_point(0.0)) < kClosedGap;
  speed_ = SpeedProfile(record.speed, loop ? course_length_ : 0.0);

  anchors_.push_back({0.0, 0.0});
  for (const CutRecord& c : cuts_) {
    const double before = travelled(anchors_.size() - 1, c.time_s);
    double u = 0.0;
    switch (c.kind) {
      case CutRecord::Kind::to_arc_length:
        u = c.metres;
        break;
      case CutRecord::Kind::to_position:
        u = nearest_u(c.position);
        break;
      case CutRecord::Kind::jump_ahead:
        u = settle(before) + c.metres;
        break;
    }
    anchors_.push_back({c.time_s, settle(u)});
  }
  anchors_complete_ = periodic_.every_s <= 0.0;
}

double CameraPath::settle(double u) const {
  if (at_end_ == CameraPathRecord::AtEnd::loop) {
    const double w = u - std::floor(u / course_length_) * course_length_;
    return w < course_length_ ? w : 0.0;
  }
  return std::clamp(u, 0.0, course_length_);
}

double CameraPath::nearest_u(const glm::dvec3& p) const {
  if (type_ == CameraPathRecord::Type::keyframes) return spline_.closest_s(p);
  return std::clamp(direction_ * (road_->closest_s(p) - start_s_), 0.0, course_length_);
}

glm::dvec3 CameraPath::course_point(double u) const {
  if (type_ == CameraPathRecord::Type::recorded) return recorded_->track.positions().front();
  if (type_ == CameraPathRecord::Type::keyframes) return spline_.at(u);
  return lane_point(*road_, start_s_ + direction_ * u, direction_, lane_offset_, height_);
}

glm::dvec3 CameraPath::course_derivative(double u) const {
  if (type_ == CameraPathRecord::Type::recorded) return glm::dvec3(0.0);
  if (type_ == CameraPathRecord::Type::keyframes) return spline_.tangent(u);
  // d/du = direction * d/ds.
  return static_cast<double>(direction_) *
         lane_derivative(*road_, start_s_ + direction_ * u, direction_, lane_offset_);
}

double CameraPath::travelled(std::size_t k, double time) const {
  const Anchor& a = anchors_[k];
  return speed_.advance(a.u, a.time, std::max(time, a.time));
}

std::size_t CameraPath::anchor_index(double time) const {
  // Periodic cut n happens at first_s + n * every_s: a product, so cut times never drift.
  while (!anchors_complete_) {
    const std::size_t n = anchors_.size() - 1;
    const double tc = periodic_.first_s + static_cast<double>(n) * periodic_.every_s;
    if (tc > time) break;
    const double before = settle(travelled(anchors_.size() - 1, tc));
    const double u = periodic_.targets_m.empty()
                         ? before + periodic_.jump_ahead_m
                         : periodic_.targets_m[n % periodic_.targets_m.size()];
    anchors_.push_back({tc, settle(u)});
  }
  auto it = std::upper_bound(anchors_.begin(), anchors_.end(), time,
                             [](double t, const Anchor& a) { return t < a.time; });
  return it == anchors_.begin() ? 0 : static_cast<std::size_t>(it - anchors_.begin()) - 1;
}

CameraState CameraPath::state(double time, double previous_time) const {
  time = std::max(time, 0.0);
  previous_time = std::clamp(previous_time, 0.0, time);
  if (type_ == CameraPathRecord::Type::recorded) {
    const RecordedTrack::State at = recorded_->track.at(time);
    CameraState s;
    s.time = time;
    s.position = at.position;
    s.velocity = at.velocity;
    s.cut = recorded_->track.cut_in(previous_time, time);
    return s;
  }
  const std::size_t k_prev = anchor_index(previous_time);
  const std::size_t k = anchor_index(time);
  CameraState s;
  s.time = time;
  s.cut = k != k_prev;
  const double u = travelled(k, time);
  double speed = speed_.speed(u, time);
  double at = u;
  if (at_end_ == CameraPathRecord::AtEnd::loop) {
    const double laps = std::floor(u / course_length_);
    at = u - laps * course_length_;
    if (!s.cut && !closed_) {
      s.cut = std::floor(travelled(k, previous_time) / course_length_) != laps;
    }
  } else if (u >= course_length_) {
    at = course_length_;
    speed = 0.0;  // held at the end
  }
  s.position = course_point(at);
  s.velocity = speed * course_derivative(at);
  return s;
}

}  // namespace ambisim
