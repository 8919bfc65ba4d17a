#pragma once
// Recorded motion from CSV telemetry (SPEC section 10): a camera flight (time,x,y,z[,cut]) and
// receiver tracks (id,time,x,y,z), in seconds of simulated time and world metres, the columns
// named by a required header line in any order. Between samples the position is linear in time
// and the velocity is that segment's slope, so a frame that falls on a sample time is exactly
// at that sample. Both formats may also carry the velocity (columns vx,vy,vz, m/s, all three
// or none), as telemetry often does: then a sample's velocity is the recorded one and it is
// linear in time between samples (the position stays linear). Files are read with the
// standard library; every error names the CSV file and the line, and the file's bytes are
// hashed so that a scenario's hash follows its recordings.
//
// Camera (`RecordedCamera`, replayed by CameraPath): before the first sample the camera stands
// at it, after the last at the last (velocity 0). `cut` = 1 on a sample is a teleport at that
// sample's time: the segment into it is not interpolated (the camera keeps the velocity it
// had, from the segment before or as recorded, until the cut) and CameraState::cut is set on
// the first frame at or after that time. A cut on the first sample has nothing to cut from and
// changes nothing.
//
// Receivers (`RecordedReceivers`): each id is one receiver, alive from its first to its last
// sample (both included), samples strictly increasing in time per id; rows of different ids
// may interleave.
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

#include "sim/base/json_reader.h"

namespace ambisim {

// Piecewise-linear motion through time-stamped samples (times strictly increasing).
class RecordedTrack {
 public:
  struct State {
    glm::dvec3 position{0.0};
    glm::dvec3 velocity{0.0};
  };

  RecordedTrack() = default;
  // `cuts` is empty (no cuts) or one flag per sample; `velocities` empty (from the
  // interpolation) or one recorded velocity per sample.
  RecordedTrack(std::vector<double> times, std::vector<glm::dvec3> positions,
                std::vector<bool> cuts = {}, std::vector<glm::dvec3> velocities = {});

  // Position and velocity at `time`: exactly a sample's position at its time; held (velocity
  // 0) before the first and after the last sample.
  State at(double time) const;
  // True if a cut sample (other than the first) lies in (t0, t1].
  bool cut_in(double t0, double t1) const;

  std::size_t size() const { return times_.size(); }
  double first_time() const { return times_.front(); }
  double last_time() const { return times_.back(); }
  const std::vector<double>& times() const { return times_; }
  const std::vector<glm::dvec3>& positions() const { return positions_; }

 private:
  std::vector<double> times_;
  std::vector<glm::dvec3> positions_;
  std::vector<bool> cuts_;
  std::vector<glm::dvec3> velocities_;        // recorded, per sample (empty: none)
  std::vector<glm::dvec3> segment_velocity_;  // segment k: from sample k to k + 1
  std::vector<bool> segment_moves_;           // interpolated (false: a cut ends it)
};

// What a scenario section read from a CSV file: where it came from and its content hash.
struct RecordingSource {
  std::string file;                // the CSV path as resolved (relative to the scenario file)
  std::uint64_t content_hash = 0;  // of the file's bytes
};

struct RecordedCamera {
  RecordingSource source;
  RecordedTrack track;
};

struct RecordedReceivers {
  RecordingSource source;
  std::vector<std::string> ids;       // per track, as written in the file
  std::vector<RecordedTrack> tracks;  // sorted by first sample time, then first row in the file
};

// Column sets, for messages and documentation.
inline const std::vector<std::string> kCameraCsvColumns{"time", "x", "y", "z"};
inline const std::vector<std::string> kReceiverCsvColumns{"id", "time", "x", "y", "z"};
inline const std::vector<std::string> kVelocityCsvColumns{"vx", "vy", "vz"};

// Parse CSV text; `file` names it in errors (InputError(file, "line N", ...)). The limits:
// times finite within +-1e9 s, coordinates within +-1e10 m, velocities within +-1e6 m/s, at
// least one sample, and for receivers at most `max_live` alive at any one time.
RecordedCamera parse_camera_csv(std::string_view text, const std::string& file);
RecordedReceivers parse_receiver_csv(std::string_view text, const std::string& file, int max_live);

// Reads the CSV file named by the string at `key` of `r`, a path relative to the directory of
// the scenario file r.file() (or absolute). A missing or unreadable file is an InputError at
// the JSON path; errors inside the file name the CSV file and its line.
std::shared_ptr<const RecordedCamera> read_recorded_camera(ObjectReader& r, std::string_view key);
std::shared_ptr<const RecordedReceivers> read_recorded_receivers(ObjectReader& r,
                                                                 std::string_view key,
                                                                 int max_live);

// A camera recording in the format parse_camera_csv reads: "time,x,y,z,vx,vy,vz,cut" and one
// row per sample, every number with 17 significant digits so that it reads back bit for bit.
struct CameraSample {
  double time = 0.0;
  glm::dvec3 position{0.0};
  glm::dvec3 velocity{0.0};
  bool cut = false;
};
std::string camera_csv(const std::vector<CameraSample>& samples);

}  // namespace ambisim
