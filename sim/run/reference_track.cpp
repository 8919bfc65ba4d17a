#include "sim/run/reference_track.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <map>

#include "sim/metrics/accuracy.h"
#include "sim/render/capture.h"
#include "sim/scenario/receiver_sample.h"
#include "sim/scenario/scenario.h"
#include "sim/scenario/scenario_motion.h"
#include "sim/sh/irradiance_reference.h"
#include "sim/sh/sh_projection.h"
#include "sim/world/illumination.h"
#include "sim/world/lighting_model.h"
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
      // Only the receivers the referee scores (all of them unless the scenario samples).
      ReferenceTrack::FrameSpan span{track->ids.size(), 0};
      for (const auto& r : motion.receivers()) {
        if (!receiver_scored(scenario.reference, r)) continue;
        ++span.count;
        by_receiver[r.id].push_back({r.position, motion.current().frame.time, track->ids.size()});
        track->ids.push_back(r.id);
        track->positions.push_back(r.position);
      }
      track->frames.push_back(span);
    }
  }
  track->irradiance.assign(track->ids.size() * nn, Rgb(0.0f));
  track->sh.assign(track->ids.size(), Sh9Rgb{});

  // Pass 2: captures at key samples, interpolation in between. Under static lighting a capture
  // depends only on the position (static receivers are captured once); under changing light on
  // the position and the time. Captures are made in time order within each phase, so the
  // lighting (a moving sun's shadow maps) advances once per phase instead of once per receiver.
  const IrradianceIntegrator integrator(scenario.reference.face_size, track->normals);
  const ShProjector& projector = projector_for(scenario.reference.face_size);
  track->face_size = scenario.reference.face_size;
  LightingModel lighting(world);
  const bool timeless = lighting.is_static();
  struct Captured {
    std::vector<Rgb> irradiance;
    Sh9Rgb sh;
  };
  std::map<std::pair<PositionKey, std::uint64_t>, Captured> cache;
  auto reference_at = [&](const glm::dvec3& p, double time) -> const Captured& {
    const std::uint64_t tkey = timeless ? 0 : std::bit_cast<std::uint64_t>(time);
    auto [it, inserted] = cache.try_emplace({key_of(p), tkey});
    if (inserted) {
      const Illumination il(world, lighting.state_at(time));
      const CubeMap cube = capture(il, p, scenario.reference.face_size);
      it->second.irradiance = integrator.integrate(cube);
      it->second.sh = projector.project(cube);
      ++track->captures;
    }
    return it->second;
  };
  const double interval = scenario.reference.interval_s;
  auto store = [&](const Sample& smp) {
    const Captured& c = reference_at(smp.position, smp.time);
    std::copy(c.irradiance.begin(), c.irradiance.end(), track->irradiance.begin() + smp.slot * nn);
    track->sh[smp.slot] = c.sh;
  };
  // Stores the given (receiver, sample) pairs in time order (then slot order: deterministic).
  using Job = std::pair<std::uint64_t, std::size_t>;
  auto store_in_time_order = [&](std::vector<Job>& jobs) {
    std::sort(jobs.begin(), jobs.end(), [&](const Job& a, const Job& b) {
      const Sample& sa = by_receiver[a.first][a.second];
      const Sample& sb = by_receiver[b.first][b.second];
      return sa.time < sb.time || (sa.time == sb.time && sa.slot < sb.slot);
    });
    for (const Job& j : jobs) store(by_receiver[j.first][j.second]);
  };
  // Phase 1: key samples of every receiver: all of them, or the first in each time bucket
  // plus the last one.
  std::map<std::uint64_t, std::vector<std::size_t>> keys_of;
  {
    std::vector<Job> jobs;
    for (auto& [id, samples] : by_receiver) {
      std::vector<std::size_t>& keys = keys_of[id];
      for (std::size_t k = 0; k < samples.size(); ++k) {
        const bool last = k + 1 == samples.size();
        if (interval <= 0.0 || k == 0 || last ||
            std::floor(samples[k].time / interval) != std::floor(samples[k - 1].time / interval)) {
          keys.push_back(k);
          jobs.push_back({id, k});
        }
      }
    }
    store_in_time_order(jobs);
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
  // An interval whose ends differ has its midpoint captured; if linear interpolation of the
  // ends mispredicts the midpoint, both halves are intervals of the next wave. Each interval's
  // fate depends only on its own ends, so refining wave by wave (the midpoints of a wave
  // captured in time order) captures exactly what a depth-first refinement would.
  struct Interval {
    std::uint64_t id;
    std::size_t lo, hi;
  };
  std::vector<Interval> wave;
  for (auto& [id, samples] : by_receiver) {
    const std::vector<std::size_t>& keys = keys_of[id];
    for (std::size_t a = 0; a + 1 < keys.size(); ++a) wave.push_back({id, keys[a], keys[a + 1]});
  }
  std::map<std::uint64_t, std::vector<std::size_t>> added_of;
  while (!wave.empty()) {
    std::vector<Interval> split;
    std::vector<Job> jobs;
    for (const Interval& iv : wave) {
      const auto& samples = by_receiver[iv.id];
      if (iv.hi - iv.lo < 2 || !differs(samples[iv.lo], samples[iv.hi])) continue;
      jobs.push_back({iv.id, iv.lo + (iv.hi - iv.lo) / 2});
      split.push_back(iv);
    }
    store_in_time_order(jobs);
    std::vector<Interval> next;
    for (const Interval& iv : split) {
      const auto& samples = by_receiver[iv.id];
      const std::size_t mid = iv.lo + (iv.hi - iv.lo) / 2;
      added_of[iv.id].push_back(mid);
      if (!mispredicted(samples[iv.lo], samples[mid], samples[iv.hi])) continue;
      next.push_back({iv.id, iv.lo, mid});
      next.push_back({iv.id, mid, iv.hi});
    }
    wave = std::move(next);
  }
  for (auto& [id, keys] : keys_of) {
    const auto it = added_of.find(id);
    if (it == added_of.end()) continue;
    keys.insert(keys.end(), it->second.begin(), it->second.end());
    std::sort(keys.begin(), keys.end());
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
