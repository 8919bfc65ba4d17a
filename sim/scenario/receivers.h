#pragma once
// Receivers: objects the planner's lookup lights (never part of captures). The camera's own
// object plus two spawners from the thesis (7.5.1): props appearing at a LOD switch near a
// forest edge (50 per second), and motorway traffic on both carriageways (10 per second); and
// receivers replayed from CSV tracks (recorded_track.h), each alive from its first to its last
// sample.
// Spawning is at a deterministic rate (a count, not a random process); positions and lanes
// come from a counter-based hash of (seed, spawner, spawn index), so the same seed and the
// same frame times give the same receivers, independent of anything else.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "sim/base/json_reader.h"
#include "sim/scenario/camera_path.h"
#include "sim/scenario/landmark_ref.h"
#include "sim/scenario/recorded_track.h"
#include "sim/world/terrain_queries.h"

namespace ambisim {

enum class ReceiverKind { camera_object, lod_prop, traffic, recorded, crowd };
inline constexpr int kReceiverKinds = 5;
const char* receiver_kind_name(ReceiverKind kind);

struct Receiver {
  std::uint64_t id = 0;  // unique, increasing in spawn order; the camera object is 0
  ReceiverKind kind = ReceiverKind::camera_object;
  double spawn_time = 0.0;    // s, the frame time it appeared
  double despawn_time = 0.0;  // s: scheduled end while live (+inf if none); actual once gone
  glm::dvec3 position{0.0};   // at the last update
  glm::dvec3 velocity{0.0};   // m/s, at the last update
  double size_m = 2.0;        // diameter of the sphere a player sees (the viewed metrics)
  // Traffic motion: road arc length at spawn and lane direction (+1 / -1 along the road).
  double road_s0 = 0.0;
  int lane_direction = 0;
  double road_speed = 0.0;      // traffic: this vehicle's speed along the road (m/s)
  std::size_t track = 0;        // recorded: index into RecordedReceivers::tracks
  std::int64_t kind_order = 0;  // its place in its kind's spawn order (0: the first)
};

struct CameraObjectRecord {
  // ground: the object stands height_m above whatever is solid below it (a car ahead of a
  // driving camera); camera: it flies height_m above (negative: below) the camera, like a
  // player's aircraft, and never closer than kMinClearance to the surface.
  enum class Follow { ground, camera };
  bool enabled = true;
  double ahead_m = 8.0;   // along the camera's horizontal heading
  double height_m = 1.0;  // above the ground (follow ground) or the camera (follow camera)
  Follow follow = Follow::ground;
  double size_m = 2.0;                          // as seen by the player (a car, an aircraft)
  static constexpr double kMinClearance = 0.5;  // metres above the surface, follow camera
};

struct LodPropsRecord {
  glm::dvec3 trigger{0.0};                    // the forest edge (only x, y are used)
  std::vector<LandmarkRef> trigger_landmark;  // the trigger given as a landmark (at most one)
  double lod_distance_m = 200.0;              // horizontal camera distance that switches LOD
  double rate_per_s = 50.0;
  double band_near_m = 20.0;  // band ahead of the camera where props appear
  double band_far_m = 150.0;
  double band_half_width_m = 40.0;
  double min_height_m = 0.5;  // above the ground
  double max_height_m = 2.0;
  double lifetime_s = 30.0;
  double behind_margin_m = 10.0;  // despawned once this far behind the camera
  int max_live = 1000;
};

struct TrafficRecord {
  double rate_per_s = 10.0;  // both carriageways together
  double speed_mps = 30.0;
  // Each vehicle drives at speed_mps x (1 + speed_spread x u), u uniform in [-1, 1]: real
  // traffic is not a convoy, and equal speeds would keep same-direction cars beside the camera
  // for ever.
  double speed_spread = 0.0;
  double window_behind_m = 200.0;  // road window around the camera, in its direction of travel
  double window_ahead_m = 800.0;
  std::optional<double> lane_offset_m;  // right of the lane's direction [road_width / 4]
  double height_m = 1.0;                // above the road surface
  int max_live = 500;
  double size_m = 2.0;  // as seen by the player (a car)
};

// A game's load: a crowd on the fields (a festival): `count` props and people, all present
// from the first frame, standing in a disc around `centre`; `walking_share` of them are people
// milling at walking speed, each on its own closed loop around its home (a Lissajous figure
// of `wander_m` amplitude, so speeds vary smoothly around speed_mps), the rest stand still.
struct CrowdRecord {
  glm::dvec3 centre{0.0};                    // only x, y are used
  std::vector<LandmarkRef> centre_landmark;  // the centre given as a landmark (at most one)
  int count = 2000;
  double radius_m = 150.0;
  double walking_share = 0.5;
  double speed_mps = 1.4;
  double wander_m = 8.0;
  double height_m = 1.0;  // of a person's centre above the surface; props 0.5-1.5
  double size_m = 1.0;    // as seen by the player
};

struct RecordedReceiversRecord {
  std::shared_ptr<const RecordedReceivers> tracks;  // read from the CSV file
  double size_m = 2.0;                              // as seen by the player, every receiver
};

struct ReceiversRecord {
  std::uint64_t seed = 1;
  CameraObjectRecord camera_object;
  std::optional<LodPropsRecord> lod_props;
  std::optional<TrafficRecord> traffic;
  std::optional<RecordedReceiversRecord> recorded;
  std::optional<CrowdRecord> crowd;
};

// Reads a "receivers" object (schema in receivers.cpp); calls finish().
ReceiversRecord parse_receivers(ObjectReader& r);

// Fills a landmark trigger from the world's landmarks (landmark_ref.h); throws InputError.
void resolve_receiver_landmarks(ReceiversRecord& record, const WorldLandmarks& landmarks,
                                const std::string& file);

struct ReceiverCounters {
  std::int64_t spawned[kReceiverKinds] = {};  // by ReceiverKind
  std::int64_t despawned[kReceiverKinds] = {};
  std::int64_t suppressed[kReceiverKinds] = {};  // due by rate but over max_live
  // Recorded tracks whose whole life fell between two frames: never seen.
  std::int64_t recorded_missed = 0;
};

class ReceiverSet {
 public:
  // Throws std::invalid_argument if an enabled part needs ground height or a road that
  // `terrain` lacks. `terrain` must outlive the set.
  ReceiverSet(const ReceiversRecord& record, const TerrainQueries& terrain);

  // Advances to `time` (non-decreasing between calls): despawns, spawns, moves.
  void update(double time, const CameraState& camera);

  const std::vector<Receiver>& live() const { return live_; }  // in id order
  // Those despawned by the last update (despawn_time = that update's time).
  const std::vector<Receiver>& despawned() const { return gone_; }
  const ReceiverCounters& counters() const { return counters_; }
  // Spawns due so far by rate (spawned + suppressed), per spawner.
  std::int64_t lod_emitted() const { return lod_emitted_; }
  std::int64_t traffic_emitted() const { return traffic_emitted_; }

 private:
  void update_camera_object(double time, const CameraState& camera);
  double stand_height(double x, double y) const;
  void update_lod_props(double time, const CameraState& camera);
  void update_traffic(double time, const CameraState& camera);
  void update_recorded(double time);
  void update_crowd(double time);
  Receiver& spawn(ReceiverKind kind, double time);
  std::int64_t live_count(ReceiverKind kind) const;
  double uniform(std::uint64_t stream, std::int64_t index, int component) const;

  ReceiversRecord rec_;
  TerrainQueries terrain_;
  double lane_offset_ = 0.0;
  std::vector<Receiver> live_;
  std::vector<Receiver> gone_;
  ReceiverCounters counters_;
  std::uint64_t next_id_ = 1;
  bool started_ = false;
  double start_time_ = 0.0;
  double last_time_ = 0.0;
  glm::dvec3 heading_{1.0, 0.0, 0.0};  // horizontal; kept while the camera stands still
  // LOD spawn clock: seconds spent within lod distance, as base + (time - entered).
  bool lod_inside_ = false;
  double lod_base_ = 0.0;
  double lod_entered_ = 0.0;
  std::int64_t lod_emitted_ = 0;
  std::int64_t traffic_emitted_ = 0;
  int camera_road_dir_ = 1;
  std::size_t next_track_ = 0;  // recorded: the first track not yet spawned (or missed)
};

}  // namespace ambisim
