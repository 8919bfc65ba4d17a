#pragma once
// Where the camera is at each moment: a keyframed spline or a lane of the world road, moved
// along by a speed profile, with optional cuts (teleports); or a recorded flight replayed from
// CSV telemetry (recorded_track.h). Evaluation is a pure function of time (plus a cache of cut
// anchors), so frame rate never changes where the camera is.
#include <memory>
#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "sim/base/json_reader.h"
#include "sim/metrics/view_weights.h"
#include "sim/scenario/landmark_ref.h"
#include "sim/scenario/recorded_track.h"
#include "sim/scenario/speed_profile.h"
#include "sim/world/spline.h"
#include "sim/world/terrain_queries.h"

namespace ambisim {

struct CameraState {
  double time = 0.0;
  glm::dvec3 position{0.0};
  glm::dvec3 velocity{0.0};  // m/s; on a cut frame, the velocity of the new motion
  bool cut = false;          // true on the first frame after a teleport
};

struct CutRecord {
  enum class Kind { to_arc_length, to_position, jump_ahead };
  double time_s = 0.0;  // > 0
  Kind kind = Kind::to_arc_length;
  double metres = 0.0;       // to_arc_length: course coordinate; jump_ahead: distance
  glm::dvec3 position{0.0};  // to_position: jumps to the course point nearest this
};

struct PeriodicCutRecord {
  double every_s = 0.0;           // 0 = none
  double first_s = 0.0;           // time of the first cut
  double jump_ahead_m = 0.0;      // used when targets_m is empty
  std::vector<double> targets_m;  // course coordinates, cycled
};

struct CameraPathRecord {
  enum class Type { keyframes, road, recorded };
  enum class AtEnd { hold, loop };
  Type type = Type::keyframes;
  // keyframes
  std::vector<glm::dvec3> points;
  bool z_above_ground = false;
  // road
  std::optional<double> lane_offset_m;  // default road_width / 4 (middle of the right lane)
  double height_m = 1.5;
  double start_arc_length_m = 0.0;
  int direction = 1;
  // recorded: the samples read from the CSV file (shared by the copies of a scenario); none of
  // the fields below but the view apply
  std::shared_ptr<const RecordedCamera> recorded;
  // keyframes and road
  SpeedProfileRecord speed;
  AtEnd at_end = AtEnd::hold;
  std::vector<CutRecord> cuts;  // sorted by time, strictly increasing
  PeriodicCutRecord periodic;
  // The player's view: the lens, and where it looks (along the camera's heading unless
  // look_at is given).
  ViewSpec view;
  std::optional<glm::dvec3> look_at;
  // Positions given as landmarks (landmark_ref.h), filled in by resolve_camera_landmarks:
  // indices into points, into cuts (to_position), and look_at (index 0).
  std::vector<LandmarkRef> point_landmarks, cut_landmarks, look_at_landmark;
};

// Fills the landmark positions of `record` from the world's landmarks; throws InputError(file,
// path) for a landmark this world lacks.
void resolve_camera_landmarks(CameraPathRecord& record, const WorldLandmarks& landmarks,
                              const std::string& file);

// Reads a "camera" object (schema in the file comment of camera_path.cpp); calls finish().
CameraPathRecord parse_camera_path(ObjectReader& r);

class CameraPath {
 public:
  // Throws std::invalid_argument if the record needs a road or ground height that `terrain`
  // lacks, or the road start lies off the road.
  CameraPath(const CameraPathRecord& record, const TerrainQueries& terrain);

  // State at `time` >= 0. `cut` is set if a teleport happened in (previous_time, time]; pass
  // previous_time == time on the first frame. Not thread-safe (periodic cuts fill a cache).
  CameraState state(double time, double previous_time) const;

  // The course: the distance coordinate u in [0, course_length()] from where the path starts,
  // in its direction of travel (keyframes: spline arc length; road: metres from the start;
  // recorded: no course, a length of 0 at the first sample).
  double course_length() const { return course_length_; }
  glm::dvec3 course_point(double u) const;
  // d(course_point)/du: the unit tangent for keyframes; for an offset lane, slightly off unit.
  glm::dvec3 course_derivative(double u) const;

 private:
  struct Anchor {
    double time;
    double u;  // course coordinate right after the cut
  };
  std::size_t anchor_index(double time) const;  // last anchor with anchor.time <= time
  double settle(double u) const;                // wrap (loop) or clamp (hold) into the course
  double nearest_u(const glm::dvec3& p) const;
  // Unwrapped course coordinate at `time` under anchor k.
  double travelled(std::size_t k, double time) const;

  CameraPathRecord::Type type_;
  CameraPathRecord::AtEnd at_end_;
  Spline3 spline_;
  const Spline3* road_ = nullptr;
  std::shared_ptr<const RecordedCamera> recorded_;
  double lane_offset_ = 0.0;
  double height_ = 0.0;
  double start_s_ = 0.0;
  int direction_ = 1;
  double course_length_ = 0.0;
  bool closed_ = false;  // a looping course whose end meets its start: wraps are not cuts
  SpeedProfile speed_;
  std::vector<CutRecord> cuts_;
  PeriodicCutRecord periodic_;
  mutable std::vector<Anchor> anchors_;
  mutable bool anchors_complete_ = false;
};

}  // namespace ambisim
