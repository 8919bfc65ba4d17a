#include "sim/reference_track.h"

#include <bit>
#include <cmath>
#include <map>

#include "sim/accuracy.h"
#include "sim/capture.h"
#include "sim/irradiance_reference.h"
#include "sim/scenario.h"
#include "sim/scenario_motion.h"
#include "sim/world.h"

namespace ambisim {
namespace {

using PositionKey = std::array<std::uint64_t, 3>;
PositionKey key_of(const glm::dvec3& p) {
  return {std::bit_cast<std::uint64_t>(p.x), std::bit_cast<std::uint64_t>(p.y),
          std::bit_cast<std::uint64_t>(p.z)};
}

struct Sample {
  glm::dvec3 position;
  double time;
  std::size_t slot;
};

}  // namespace

std::shared_ptr<const ReferenceTrack> compute_reference_track(const Scenario& scenario,
                                                              const World& world) {
  auto track = std::make_shared<ReferenceTrack>();
  track->normals = scenario.metrics.normals;
  const std::size_t nn = track->normals.size();

  // Pass 1: the motion, recording every receiver sample, grouped per receiver.
  std::map<std::uint64_t, std::vector<Sample>> by_receiver;
  {
    ScenarioMotion motion(scenario, world);
    while (motion.next()) {
      ReferenceTrack::FrameSpan span{track->ids.size(), motion.receivers().size()};
      for (const auto& r : motion.receivers()) {
        by_receiver[r.id].push_back({r.position, motion.current().frame.time, track->ids.size()});
        track->ids.push_back(r.id);
      }
      track->frames.push_back(span);
    }
  }
  track->irradiance.assign(track->ids.size() * nn, Rgb(0.0f));

  // Pass 2: captures at key samples (cached by exact position), interpolation in between.
  const IrradianceIntegrator integrator(scenario.reference.face_size, track->normals);
  std::map<PositionKey, std::vector<Rgb>> cache;
  auto reference_at = [&](const glm::dvec3& p) -> const std::vector<Rgb>& {
    auto [it, inserted] = cache.try_emplace(key_of(p));
    if (inserted) {
      it->second = integrator.integrate(capture(world, p, scenario.reference.face_size));
      ++track->captures;
    }
    return it->second;
  };
  const double interval = scenario.reference.interval_s;
  for (auto& [id, samples] : by_receiver) {
    // Key samples: all of them, or the first in each time bucket plus the last one.
    std::vector<std::size_t> keys;
    for (std::size_t k = 0; k < samples.size(); ++k) {
      const bool last = k + 1 == samples.size();
      if (interval <= 0.0 || k == 0 || last ||
          std::floor(samples[k].time / interval) != std::floor(samples[k - 1].time / interval)) {
        keys.push_back(k);
      }
    }
    for (std::size_t a = 0; a < keys.size(); ++a) {
      const Sample& s = samples[keys[a]];
      const std::vector<Rgb>& v = reference_at(s.position);
      std::copy(v.begin(), v.end(), track->irradiance.begin() + s.slot * nn);
    }
    for (std::size_t a = 0; a + 1 < keys.size(); ++a) {
      const Sample& s0 = samples[keys[a]];
      const Sample& s1 = samples[keys[a + 1]];
      for (std::size_t k = keys[a] + 1; k < keys[a + 1]; ++k) {
        const double f = (samples[k].time - s0.time) / (s1.time - s0.time);
        for (std::size_t m = 0; m < nn; ++m) {
          const Rgb& e0 = track->irradiance[s0.slot * nn + m];
          const Rgb& e1 = track->irradiance[s1.slot * nn + m];
          track->irradiance[samples[k].slot * nn + m] = e0 + static_cast<float>(f) * (e1 - e0);
        }
        ++track->slots_interpolated;
      }
    }
  }
  // One display exposure for the whole scenario, from the reference alone.
  track->exposure = scenario.metrics.exposure > 0.0
                        ? scenario.metrics.exposure
                        : reference_exposure(track->irradiance, scenario.metrics.exposure_key);
  return track;
}

}  // namespace ambisim
