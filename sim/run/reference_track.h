#pragma once
// The truth every planner is scored against: the irradiance at each live receiver, at each
// frame, for the metric normals, from a capture at the receiver's exact position (exact
// cosine-weighted integral of the cube, no SH truncation). It depends only on the world and
// the receivers' trajectories, never on a planner or a budget, so one track serves every
// planner and budget of a scenario variant (see reference_cache.h).
//
// Cost control (ReferenceSettings): a static receiver is captured once; with interval_s > 0 a
// moving receiver is captured on a time grid (the first frame in each interval, and its last
// frame), refined where the displayed colour changes abruptly between keys, and interpolated
// linearly in time between keys. tests/sim/test_reference_track measures what that shortcut
// costs in CIEDE2000.
#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <vector>

#include <glm/vec3.hpp>

#include "sim/colour/rgb.h"
#include "sim/sh/sh9.h"

namespace ambisim {

struct Scenario;
class World;

struct ReferenceTrack {
  std::vector<glm::dvec3> normals;
  struct FrameSpan {
    std::size_t begin = 0;  // first receiver slot of this frame
    // live receivers the referee scores (in id order, as ScenarioMotion gives them; every
    // live one unless the scenario samples them: receiver_sample.h)
    std::size_t count = 0;
  };
  std::vector<FrameSpan> frames;
  std::vector<std::uint64_t> ids;  // receiver id per slot
  std::vector<Rgb> irradiance;     // slot-major, normals.size() values per slot
  double exposure = 1.0;           // display exposure from the reference (Reinhard key 0.18)
  std::int64_t captures = 0;       // reference captures rendered
  std::int64_t slots_interpolated = 0;

  const Rgb* values(std::size_t slot) const { return &irradiance[slot * normals.size()]; }

  // The reference capture of each slot projected to SH9 (interpolated in time like the
  // irradiance between captured slots): the best the SH9 representation can do at that
  // receiver. The oracle is served from these, so it is the representation's ceiling against
  // exactly this reference, at no extra rendering cost.
  int face_size = 0;
  std::vector<Sh9Rgb> sh;
  std::vector<glm::dvec3> positions;  // receiver position per slot
  // The slot of a receiver of frame `frame` at exactly position p, or -1.
  std::ptrdiff_t find_slot(std::size_t frame, const glm::dvec3& p) const;
};

// Runs the scenario's motion (no planner) and computes the track. Single-threaded and
// deterministic.
std::shared_ptr<const ReferenceTrack> compute_reference_track(const Scenario& scenario,
                                                              const World& world);

}  // namespace ambisim
