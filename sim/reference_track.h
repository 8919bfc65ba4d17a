#pragma once
// The truth every planner is scored against: the irradiance at each live receiver, at each
// frame, for the metric normals, from a capture at the receiver's exact position (exact
// cosine-weighted integral of the cube, no SH truncation). It depends only on the world and
// the receivers' trajectories, never on a planner or a budget, so one track serves every
// planner and budget of a scenario variant (see reference_cache.h).
//
// Cost control (ReferenceSettings): a static receiver is captured once; with interval_s > 0 a
// moving receiver is captured on a time grid (the first frame in each interval, and its last
// frame) and interpolated linearly in time between those keys. tests/sim/test_reference_track
// measures what that shortcut costs in CIEDE2000.
#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <vector>

#include <glm/vec3.hpp>

#include "sim/rgb.h"
#include "sim/sh9.h"

namespace ambisim {

struct Scenario;
class World;

struct ReferenceTrack {
  std::vector<glm::dvec3> normals;
  struct FrameSpan {
    std::size_t begin = 0;  // first receiver slot of this frame
    std::size_t count = 0;  // live receivers (in id order, as ScenarioMotion gives them)
  };
  std::vector<FrameSpan> frames;
  std::vector<std::uint64_t> ids;  // receiver id per slot
  std::vector<Rgb> irradiance;     // slot-major, normals.size() values per slot
  double exposure = 1.0;           // display exposure from the reference (Reinhard key 0.18)
  std::int64_t captures = 0;       // reference captures rendered
  std::int64_t slots_interpolated = 0;

  const Rgb* values(std::size_t slot) const { return &irradiance[slot * normals.size()]; }

  // Memo of every reference capture, projected to SH9, by exact position (bit pattern). A
  // capture at the same position and resolution is the same cube, so the oracle, which
  // captures at the reference resolution, reuses these instead of rendering them again.
  int face_size = 0;
  std::map<std::array<std::uint64_t, 3>, Sh9Rgb> sh_by_position;
  const Sh9Rgb* find_sh(const glm::dvec3& p) const;
};

// Runs the scenario's motion (no planner) and computes the track. Single-threaded and
// deterministic.
std::shared_ptr<const ReferenceTrack> compute_reference_track(const Scenario& scenario,
                                                              const World& world);

}  // namespace ambisim
