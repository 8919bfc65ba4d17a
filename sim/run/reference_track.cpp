#include "sim/run/reference_track.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <map>

#include "sim/metrics/accuracy.h"
#include "sim/render/capture.h"
#include "sim/scenario/scenario.h"
#include "sim/scenario/scenario_motion.h"
#include "sim/sh/irradiance_reference.h"
#include "sim/sh/sh_projection.h"
#include "sim/world/world.h"

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

std::ptrdiff_t ReferenceTrack::find_slot(std::size_t frame, const glm::dvec3& p) const {
  if (frame >= frames.size()) return -1;
  const FrameSpan& span = frames[frame];
  for (std::size_t k = span.begin; k < span.begin + span.count; ++k) {
    if (positions[k] == p) return static_cast<std::ptrdiff_t>(k);
  }
  return -1;
}

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
        track->positions.push_back(r.position);
      }
      track->frames.push_back(span);
    }
  }
  track->irradiance.assign(track->ids.size() * nn, Rgb(0.0f));
  track->sh.assign(track->ids.size(), Sh9Rgb{});

  // Pass 2: captures at key samples (cached by exact position), interpolation in between.
  const IrradianceIntegrator integrator(scenario.reference.face_size, track->normals);
  const ShProjector& projector = projector_for(scenario.reference.face_size);
  track->face_size = scenario.reference.face_size;
  struct Captured {
    std::vector<Rgb> irradiance;
    Sh9Rgb sh;
  };
  std::map<PositionKey, Captured> cache;
  auto reference_at = [&](const glm::dvec3& p) -> const Captured& {
    auto [it, inserted] = cache.try_emplace(key_of(p));
    if (inserted) {
      const CubeMap cube = capture(world, p, scenario.reference.face_size);
      it->second.irradiance = integrator.integrate(cube);
      it->second.sh = projector.project(cube);
      ++track->captures;
    }
    return it->second;
  };
  const double interval = scenario.reference.interval_s;
  auto store = [&](const Sample& smp) {
    const Captured& c = reference_at(smp.position);
    std::copy(c.irradiance.begin(), c.irradiance.end(), track->irradiance.begin() + smp.slot * nn);
    track->sh[smp.slot] = c.sh;
  };
  // Phase 1: key samples of every receiver: all of them, or the first in each time bucket
  // plus the last one.
  std::map<std::uint64_t, std::vector<std::size_t>> keys_of;
  for (auto& [id, samples] : by_receiver) {
    std::vector<std::size_t>& keys = keys_of[id];
    for (std::size_t k = 0; k < samples.size(); ++k) {
      const bool last = k + 1 == samples.size();
      if (interval <= 0.0 || k == 0 || last ||
          std::floor(samples[k].time / interval) != std::floor(samples[k - 1].time / interval)) {
        keys.push_back(k);
        store(samples[k]);
      }
    }
  }
  // The display exposure, from the key samples (with every frame keyed: from all of them).
  {
    std::vector<Rgb> keyed;
    for (auto& [id, samples] : by_receiver) {
      for (std::size_t k : keys_of[id]) {
        const Rgb* v = &track->irradiance[samples[k].slot * nn];
        keyed.insert(keyed.end(), v, v + nn);
      }
    }
    track->exposure = scenario.metrics.exposure > 0.0
                          ? scenario.metrics.exposure
                          : reference_exposure(keyed, scenario.metrics.exposure_key);
  }
  // Phase 2: adaptive refinement. Where the displayed colour of two neighbouring keys differs
  // by more than refine_de at any normal, the frame between them is captured too, recursively,
  // so abrupt true changes (a shadow edge, a cutting wall) are resolved frame by frame and only
  // smooth stretches are interpolated.
  // True if, at any normal, the displayed colour `expected(n)` differs from sample s's by more
  // than refine_de.
  auto departs = [&](auto&& expected, const Sample& s) {
    for (std::size_t n = 0; n < nn; ++n) {
      if (display_difference(expected(n), track->irradiance[s.slot * nn + n], track->exposure) >
          scenario.reference.refine_de) {
        return true;
      }
    }
    return false;
  };
  auto value = [&](const Sample& s) {
    return [&track, &s, nn](std::size_t n) { return track->irradiance[s.slot * nn + n]; };
  };
  auto differs = [&](const Sample& a, const Sample& b) { return departs(value(a), b); };
  // A midpoint the linear interpolation of its interval's ends predicts to within refine_de
  // (at every normal) shows the change is smooth there: its halves are interpolated, not
  // captured again.
  auto mispredicted = [&](const Sample& a, const Sample& m, const Sample& b) {
    const float f = static_cast<float>((m.time - a.time) / (b.time - a.time));
    const auto lerp = [&](std::size_t n) {
      const Rgb& e0 = track->irradiance[a.slot * nn + n];
      const Rgb& e1 = track->irradiance[b.slot * nn + n];
      return e0 + f * (e1 - e0);
    };
    return departs(lerp, m);
  };
  for (auto& [id, samples] : by_receiver) {
    std::vector<std::size_t>& keys = keys_of[id];
    std::vector<std::size_t> refined;
    std::vector<std::pair<std::size_t, std::size_t>> stack;
    for (std::size_t a = 0; a + 1 < keys.size(); ++a) {
      refined.push_back(keys[a]);
      stack.assign(1, {keys[a], keys[a + 1]});
      std::vector<std::size_t> added;
      while (!stack.empty()) {
        const auto [lo, hi] = stack.back();
        stack.pop_back();
        if (hi - lo < 2 || !differs(samples[lo], samples[hi])) continue;
        const std::size_t mid = lo + (hi - lo) / 2;
        store(samples[mid]);
        added.push_back(mid);
        if (!mispredicted(samples[lo], samples[mid], samples[hi])) continue;
        stack.push_back({lo, mid});
        stack.push_back({mid, hi});
      }
      std::sort(added.begin(), added.end());
      refined.insert(refined.end(), added.begin(), added.end());
    }
    if (!keys.empty()) refined.push_back(keys.back());
    keys = std::move(refined);
  }
  // Phase 3: linear interpolation in time between consecutive keys.
  for (auto& [id, samples] : by_receiver) {
    const std::vector<std::size_t>& keys = keys_of[id];
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
        track->sh[samples[k].slot] =
            sh_lerp(track->sh[s0.slot], track->sh[s1.slot], static_cast<float>(f));
        ++track->slots_interpolated;
      }
    }
  }
  return track;
}
}  // namespace ambisim
