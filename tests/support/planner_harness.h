#pragma once
// A stand-in for the simulator for planner unit tests under changing light: the camera stays
// where the test puts it, captures render from closed-form light fields after 6 frames (12
// with a lamp layer), and the world reports the rates and the lighting the test sets.
#include <cmath>
#include <functional>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

#include "sim/planner.h"

namespace ambisim::test {

inline constexpr double kFrame = 1.0 / 60.0;

inline Sh9Rgb constant_sh(const Rgb& v) {
  Sh9Rgb sh;
  sh.c[0] = v;
  return sh;
}

// The world's side: what it reports and what captures see.
struct TestWorld {
  WorldQueries queries;
  LightingInfo info;                                         // at every time
  std::function<double(const glm::dvec3&, double)> rate;     // lighting_change_at
  std::function<Rgb(const glm::dvec3&, double)> base_light;  // a capture's sun and sky
  std::function<Rgb(const glm::dvec3&)> lamp_light;          // the lamps at full power
  std::function<double(double)> lamp_level = [](double) { return 0.0; };
  std::function<double(double)> lamp_rate = [](double) { return 0.0; };

  TestWorld(const TestWorld&) = delete;  // the queries point at this one
  TestWorld() {
    rate = [](const glm::dvec3&, double) { return 0.0; };
    base_light = [](const glm::dvec3&, double) { return Rgb(1.0f); };
    lamp_light = [](const glm::dvec3&) { return Rgb(0.0f); };
    info.sun_on = false;
    info.sky_sh = constant_sh(Rgb(1.0f));
    queries.lighting_static = false;
    queries.lighting = [this](double t) {
      LightingInfo i = info;
      i.lamp_level = lamp_level(t);
      i.lamp_change_rate = lamp_rate(t);
      i.change_rate = std::max(i.sun_sky_change_rate, i.lamp_change_rate);
      return i;
    };
    queries.lighting_change_at = [this](const glm::dvec3& p, double t) { return rate(p, t); };
  }
};

struct Capture {
  CaptureRequest request;
  double start = 0.0;
  std::int64_t done_frame = 0;
};

// Drives a planner frame by frame with the camera at `camera`.
struct Harness {
  Harness(Planner& p, TestWorld& w) : planner(p), world(w) {}
  Planner& planner;
  TestWorld& world;
  glm::dvec3 camera{0.0, 0.0, 1.2};
  std::int64_t frame = 0;
  std::vector<Capture> flight;
  std::vector<std::pair<double, CaptureRequest>> started;  // (time, request)

  double time() const { return static_cast<double>(frame) * kFrame; }

  void step() {
    FrameContext ctx;
    ctx.frame = frame;
    ctx.time = time();
    ctx.dt = kFrame;
    ctx.camera_position = camera;
    ctx.faces_per_frame = 1.0;
    ctx.startable_captures = flight.size() < 2 ? 1 : 0;
    ctx.world = &world.queries;
    auto req = planner.plan(ctx);
    for (std::size_t k = 0; k < req.size(); ++k) {
      if (static_cast<int>(k) < ctx.startable_captures) {
        planner.started(req[k].tag);
        flight.push_back({req[k], ctx.time, frame + (req[k].lamp_layer ? 12 : 6)});
        started.push_back({ctx.time, req[k]});
      } else {
        planner.refused(req[k].tag);
      }
    }
    planner.update(ctx);
    for (auto it = flight.begin(); it != flight.end();) {
      if (it->done_frame <= frame) {
        FinishedProbe p;
        p.tag = it->request.tag;
        p.position = it->request.position;
        p.requested_time = it->start;
        p.finished_time = ctx.time;
        Rgb e = world.base_light(p.position, it->start);
        const Rgb lamps = world.lamp_light(p.position);
        if (it->request.lamp_layer) {
          p.has_lamp_layer = true;
          p.sh_lamps = constant_sh(lamps);
        } else {
          e += lamps * static_cast<float>(world.lamp_level(it->start));
        }
        p.sh = constant_sh(e);
        planner.deliver(p);
        it = flight.erase(it);
      } else {
        ++it;
      }
    }
    ++frame;
  }
  void run_until(double t) {
    while (time() < t) step();
  }
  // Captures started at (within 1 mm of) p between t0 and t1.
  std::vector<double> starts_at(const glm::dvec3& p, double t0, double t1) const {
    std::vector<double> out;
    for (const auto& [t, r] : started) {
      if (t >= t0 && t < t1 && glm::distance(r.position, p) < 1e-3) out.push_back(t);
    }
    return out;
  }
  std::size_t starts_between(double t0, double t1) const {
    std::size_t n = 0;
    for (const auto& [t, r] : started) n += t >= t0 && t < t1 ? 1 : 0;
    return n;
  }
};

}  // namespace ambisim::test
