#include "sim/run/simulator.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "sim/colour/ciede2000.h"
#include "sim/colour/tone_map.h"
#include "sim/metrics/coverage.h"
#include "sim/metrics/view_weights.h"
#include "sim/render/capture.h"
#include "sim/scenario/capture_budget.h"
#include "sim/scenario/frame_schedule.h"
#include "sim/scenario/receiver_sample.h"
#include "sim/scenario/scenario_motion.h"
#include "sim/sh/sh_projection.h"
#include "sim/world/illumination.h"
#include "sim/world/lighting_model.h"
#include "sim/world/world.h"
#include "sim/world/world_queries.h"

namespace ambisim {
namespace {

using Clock = std::chrono::steady_clock;
constexpr double kRouteSpacing = 10.0;  // m between points of WorldQueries::route
double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

struct InFlight {
  CaptureRequest request;
  double requested_time = 0.0;
  int faces_done = 0;
  CubeMap cube;
  const Sh9Rgb* memo = nullptr;  // a memoised reference capture (oracle only)
  CubeMap lamp_cube;             // the lamp layer (faces 6..11 of a layered capture)
  int faces() const { return request.lamp_layer ? 2 * kCubeFaces : kCubeFaces; }
};

}  // namespace

std::vector<glm::dvec3> camera_route(const ScenarioMotion& motion, double spacing_m) {
  // The camera's positions at the run's frames, kept where it has moved at least spacing_m
  // from the last point kept, and the last one. At the frames exactly (not on a grid of its
  // own): a camera recorded at every frame and replayed then gives the same route, byte for
  // byte, and so the same bake.
  std::vector<glm::dvec3> route;
  const FrameSchedule& schedule = motion.schedule();
  const std::int64_t n = schedule.frame_count();
  double prev = 0.0;
  for (std::int64_t k = 0; k < n; ++k) {
    const double t = schedule.time_of(k);
    const glm::dvec3 p = motion.camera_path().state(t, k == 0 ? t : prev).position;
    prev = t;
    if (route.empty() || glm::length(p - route.back()) >= spacing_m || k == n - 1) {
      route.push_back(p);
    }
  }
  return route;
}

std::vector<glm::dvec3> object_cells(const Scenario& scenario, const World& world, double cell_m) {
  std::map<std::pair<std::int64_t, std::int64_t>, double> first_height;
  ScenarioMotion motion(scenario, world);
  while (motion.next()) {
    for (const auto& r : motion.receivers()) {
      const auto i = static_cast<std::int64_t>(std::floor(r.position.x / cell_m));
      const auto j = static_cast<std::int64_t>(std::floor(r.position.y / cell_m));
      first_height.emplace(std::make_pair(i, j), r.position.z);
    }
  }
  std::vector<glm::dvec3> out;
  out.reserve(first_height.size());
  for (const auto& [ij, z] : first_height) {
    out.emplace_back((static_cast<double>(ij.first) + 0.5) * cell_m,
                     (static_cast<double>(ij.second) + 0.5) * cell_m, z);
  }
  return out;
}

ReceiverViewing receiver_viewing(const CameraView& view, const Receiver& r) {
  ReceiverViewing v;
  v.weight = view.screen_weight(r.position, 0.5 * r.size_m);
  const glm::dvec3 d = view.position() - r.position;
  const double len = glm::length(d);
  if (len > 0.0) v.to_camera = d / len;
  return v;
}

nlohmann::ordered_json RunTiming::to_json() const {
  nlohmann::ordered_json j;
  j["note"] = "measured wall-clock time; not deterministic, not part of the results";
  j["total_s"] = total_s;
  j["planner_us_per_frame"] = frames > 0 ? 1e6 * planner_s / static_cast<double>(frames) : 0.0;
  j["lookup_ns"] = lookups > 0 ? 1e9 * lookup_s / static_cast<double>(lookups) : 0.0;
  j["capture_s"] = capture_s;
  j["bake_s"] = bake_s;
  j["frames"] = frames;
  j["lookups"] = lookups;
  return j;
}

double FrameContext::capture_latency_s() const {
  if (faces_per_frame <= 0.0) return INFINITY;
  return std::ceil(6.0 / faces_per_frame) * dt;
}

namespace {

// One run; `reference` may be null (simulate_without_reference): then nothing is scored against
// truth, and everything the planner sees is unchanged.
RunResult run_simulation(const Scenario& scenario, const World& world,
                         const ReferenceTrack* reference, Planner& planner,
                         const SimulationOptions& options) {
  const auto t_start = Clock::now();
  RunResult result;
  MetricSettings settings = scenario.metrics;
  // Without a reference the exposure is unknown; 1 only satisfies RunMetrics, which then never
  // sees a receiver's irradiance (the exposure only scales those).
  settings.exposure = reference != nullptr ? reference->exposure : 1.0;
  result.exposure = reference != nullptr ? reference->exposure : 0.0;
  if (reference != nullptr) {
    result.reference_captures = reference->captures;
    result.reference_slots = static_cast<std::int64_t>(reference->ids.size());
    result.reference_interpolated = reference->slots_interpolated;
  }
  RunMetrics metrics(settings);
  const std::size_t nn = settings.normals.size();

  ScenarioMotion motion(scenario, world);
  CaptureBudget budget(scenario.budget);
  const int face_size = scenario.budget.face_size;
  LightingModel lighting(world);
  WorldQueries world_queries = planner_world_queries(world, &lighting);
  world_queries.route = camera_route(motion, kRouteSpacing);
  world_queries.object_cells = object_cells(scenario, world, kRouteSpacing);
  world_queries.object_cell_m = kRouteSpacing;
  const auto ground = [&world](double x, double y) { return world.ground_height(x, y); };

  std::vector<InFlight> in_flight;
  std::vector<FinishedProbe> finished;
  BakeCosts bake;
  std::vector<Planner::ReceiverView> views;
  std::vector<Rgb> planner_e(nn);
  std::vector<LookupResult> receiver_lookups, demand_lookups;
  LookupPoints receiver_points, demand_points_soa;
  std::size_t frame_index = 0;
  // Snapshots feed the views; a 30-minute run would otherwise write gigabytes of them.
  const double snapshot_every =
      options.snapshot_every_s > 0.0
          ? std::max(options.snapshot_every_s, motion.schedule().duration() / kMaxSnapshots)
          : 0.0;

  // The oracle (a planner that ignores the budget) is served the reference's own SH9 at a
  // receiver: the representation's ceiling against exactly this reference. A request that is
  // not at a receiver is rendered at the reference's resolution.
  if (reference == nullptr && planner.ignores_budget()) {
    throw std::invalid_argument("the oracle (" + planner.name() +
                                ") is served from the reference track: it cannot run without one");
  }
  const int oracle_face_size =
      reference != nullptr && reference->face_size > 0 ? reference->face_size : face_size;
  // Face k of a capture at the current frame's light: 0-5 the capture (without the lamps when
  // it has a lamp layer), 6-11 the lamp layer.
  auto render_face = [&](InFlight& c, int k, const LightingState& light) {
    if (k < kCubeFaces) {
      const Illumination il(world, light,
                            c.request.lamp_layer ? LightLayer::base : LightLayer::all);
      capture_face(il, c.request.position, static_cast<CubeFace>(k), c.cube);
    } else {
      if (c.lamp_cube.size != c.cube.size) c.lamp_cube = CubeMap(c.cube.size);
      const Illumination il(world, light, LightLayer::lamps);
      capture_face(il, c.request.position, static_cast<CubeFace>(k - kCubeFaces), c.lamp_cube);
    }
  };
  auto render_all_faces = [&](InFlight& c, std::size_t frame, const LightingState& light) {
    const auto t0 = Clock::now();
    const std::ptrdiff_t slot = reference->find_slot(frame, c.request.position);
    c.memo = slot >= 0 && !c.request.lamp_layer ? &reference->sh[static_cast<std::size_t>(slot)]
                                                : nullptr;
    // A sampled referee scores some receivers only: the oracle's answer elsewhere is never
    // scored, so it is not rendered (it is black), or a crowd would cost a capture per member
    // per frame.
    static const Sh9Rgb kUnscored{};
    if (c.memo == nullptr && !c.request.lamp_layer && scenario.reference.sample_stride > 1) {
      c.memo = &kUnscored;
    }
    if (c.memo == nullptr) {
      if (c.cube.size != oracle_face_size) c.cube = CubeMap(oracle_face_size);
      for (int f = 0; f < c.faces(); ++f) render_face(c, f, light);
    }
    c.faces_done = c.faces();
    result.timing.capture_s += seconds_since(t0);
  };
  auto finish = [&](const InFlight& c, double time) {
    const auto t0 = Clock::now();
    FinishedProbe p;
    p.tag = c.request.tag;
    p.position = c.request.position;
    p.sh = c.memo != nullptr ? *c.memo : projector_for(c.cube.size).project(c.cube);
    if (c.request.lamp_layer) {
      p.has_lamp_layer = true;
      p.sh_lamps = projector_for(c.lamp_cube.size).project(c.lamp_cube);
    }
    p.requested_time = c.requested_time;
    p.finished_time = time;
    result.timing.capture_s += seconds_since(t0);
    ++result.captures_delivered;
    return p;
  };

  std::int64_t receivers_lit = 0;  // receivers the planner lit (ids only grow)
  std::uint64_t last_id_lit = 0;
  while (motion.next()) {
    const MotionFrame& mf = motion.current();
    for (const auto& r : motion.receivers()) {
      if (receivers_lit == 0 || r.id > last_id_lit) {
        ++receivers_lit;
        last_id_lit = r.id;
      }
    }
    const std::size_t receiver_count = motion.receivers().size();
    ReferenceTrack::FrameSpan span{0, receiver_count};
    if (reference != nullptr) {
      if (frame_index >= reference->frames.size()) {
        throw std::logic_error("reference track is shorter than the run");
      }
      span = reference->frames[frame_index];
      std::size_t scored = 0;
      for (const auto& r : motion.receivers())
        scored += receiver_scored(scenario.reference, r) ? 1 : 0;
      if (span.count != scored) {
        throw std::logic_error("reference track does not match the scenario's receivers");
      }
    }
    metrics.begin_frame(mf.frame.index, mf.frame.time, mf.frame.dt, mf.camera.cut);
    budget.begin_frame(mf.frame.time);

    const LightingState& light = lighting.state_at(mf.frame.time);
    FrameCosts costs;
    std::int64_t owed = 0;
    for (const auto& c : in_flight) owed += c.faces() - c.faces_done;

    FrameContext ctx;
    ctx.frame = mf.frame.index;
    ctx.time = mf.frame.time;
    ctx.dt = mf.frame.dt;
    ctx.camera_position = mf.camera.position;
    ctx.camera_velocity = mf.camera.velocity;
    ctx.camera_cut = mf.camera.cut;
    ctx.faces_per_frame = budget.faces_per_frame(mf.frame.time);
    ctx.face_size = face_size;
    ctx.run_duration_s = motion.schedule().duration();
    ctx.world = &world_queries;
    const bool unlimited = planner.ignores_budget();
    ctx.startable_captures =
        unlimited ? 1 << 20
                  : static_cast<int>(std::max<std::int64_t>(0, budget.available() - owed));

    // 0. before the first frame: the planner's load-time captures, outside the budget.
    if (frame_index == 0) {
      const auto tb = Clock::now();
      std::vector<CaptureRequest> preload = planner.preload(ctx);
      // A capture may ask for the light of another time (a bake at several times of day). A
      // moving sun's shadow maps are computed forward in time, so those render in time order;
      // without any such request nothing is reordered and no other state is computed.
      const auto light_time = [&](const CaptureRequest& r) {
        return r.time >= 0.0 ? r.time : mf.frame.time;
      };
      const bool other_times = std::any_of(preload.begin(), preload.end(), [&](const auto& r) {
        return light_time(r) != mf.frame.time;
      });
      if (other_times) {
        std::stable_sort(preload.begin(), preload.end(), [&](const auto& a, const auto& b) {
          return light_time(a) < light_time(b);
        });
      }
      for (const auto& req : preload) {
        InFlight c{req,     0.0,      0, CubeMap(req.face_size > 0 ? req.face_size : face_size),
                   nullptr, CubeMap()};
        // `light` is the model's one current state: state_at moves it (restored below).
        const LightingState& bake_light = other_times ? lighting.state_at(light_time(req)) : light;
        for (int f = 0; f < c.faces(); ++f) render_face(c, f, bake_light);
        FinishedProbe p;
        p.tag = req.tag;
        p.position = req.position;
        p.sh = projector_for(c.cube.size).project(c.cube);
        if (req.lamp_layer) {
          p.has_lamp_layer = true;
          p.sh_lamps = projector_for(c.lamp_cube.size).project(c.lamp_cube);
        }
        planner.deliver(p);
        ++bake.captures;
        bake.faces += c.faces();
      }
      if (other_times) lighting.state_at(mf.frame.time);  // frame 0's light again, for `light`
      result.timing.bake_s += seconds_since(tb);
      metrics.bake(bake);
    }

    // 2. plan and start captures.
    auto t0 = Clock::now();
    views.clear();
    for (const auto& r : motion.receivers()) views.push_back({r.id, r.position, r.velocity});
    planner.set_receivers(views);
    std::vector<CaptureRequest> requests = planner.plan(ctx);
    int started = 0;
    for (const auto& req : requests) {
      if (req.time >= 0.0) {
        throw std::logic_error(planner.name() +
                               ": CaptureRequest::time is for preload captures only");
      }
      if (req.face_size != 0) {
        throw std::logic_error(planner.name() +
                               ": CaptureRequest::face_size is for preload captures only");
      }
      if (started < ctx.startable_captures) {
        planner.started(req.tag);
        in_flight.push_back({req, mf.frame.time, 0, unlimited ? CubeMap() : CubeMap(face_size),
                             nullptr, CubeMap()});
        ++started;
        ++result.captures_started;
      } else {
        planner.refused(req.tag);
        ++costs.captures_refused;
      }
    }
    result.timing.planner_s += seconds_since(t0);

    // 3. render faces within the budget, oldest capture first.
    finished.clear();
    std::int64_t needed = 0;
    for (const auto& c : in_flight) needed += c.faces() - c.faces_done;
    costs.faces_requested = needed;
    if (unlimited) {
      for (auto& c : in_flight) render_all_faces(c, frame_index, light);
      costs.faces_granted = needed;
    } else {
      int grant = budget.grant(static_cast<int>(std::min<std::int64_t>(needed, 1 << 30)));
      costs.faces_granted = grant;
      const auto tc = Clock::now();
      for (auto& c : in_flight) {
        while (grant > 0 && c.faces_done < c.faces()) {
          render_face(c, c.faces_done, light);
          ++c.faces_done;
          --grant;
        }
      }
      result.timing.capture_s += seconds_since(tc);
    }
    costs.faces_refused = costs.faces_requested - costs.faces_granted;
    for (auto it = in_flight.begin(); it != in_flight.end();) {
      if (it->faces_done == it->faces()) {
        finished.push_back(finish(*it, mf.frame.time));
        costs.faces_used += it->faces();
        it = in_flight.erase(it);
      } else {
        ++it;
      }
    }
    // The oracle's captures are usable at once; everyone else's from the next frame.
    t0 = Clock::now();
    if (unlimited) {
      for (const auto& p : finished) planner.deliver(p);
      finished.clear();
    }
    // 4. update.
    planner.update(ctx);
    result.timing.planner_s += seconds_since(t0);

    // 5. look up every receiver and demand point (only the lookups are timed), then score.
    const std::vector<DemandPoint> demand =
        demand_points(mf.camera.position, mf.camera.velocity, ground, settings.demand);
    // One batch per kind (Planner::lookup_many), the receivers' as a game would light them.
    receiver_points.clear();
    for (const auto& r : motion.receivers()) receiver_points.push_back(r.position);
    demand_points_soa.clear();
    for (const auto& d : demand) demand_points_soa.push_back(d.position);
    const auto tl = Clock::now();
    planner.lookup_many(receiver_points, receiver_lookups);
    planner.lookup_many(demand_points_soa, demand_lookups);
    result.timing.lookup_s += seconds_since(tl);
    result.timing.lookups += static_cast<std::int64_t>(receiver_count + demand.size());
    const CameraView view(motion.view(), mf.camera.position, mf.look);
    std::size_t slot = span.begin;  // the next scored receiver's reference slot
    const bool observe = options.on_frame && reference != nullptr;
    FrameObservation observed;
    const bool snapshot_now =
        snapshot_every > 0.0 &&
        (result.snapshots.empty() ||
         mf.frame.time >= result.snapshots.back().time + snapshot_every - 1e-9);
    std::vector<Snapshot::ReceiverLight> snapshot_light;
    for (std::size_t k = 0; k < receiver_count; ++k) {
      const Receiver& r = motion.receivers()[k];
      const LookupResult& lr = receiver_lookups[k];
      if (reference != nullptr && receiver_scored(scenario.reference, r)) {
        if (reference->ids[slot] != r.id) {
          throw std::logic_error("reference track does not match the scenario's receivers");
        }
        for (std::size_t m = 0; m < nn; ++m) {
          planner_e[m] = sh_irradiance(lr.sh, settings.normals[m]);
        }
        const ReceiverViewing viewing = receiver_viewing(view, r);
        const PopEvaluation ev =
            metrics.receiver(r.id, planner_e, std::span<const Rgb>(reference->values(slot), nn), lr,
                             viewing, receiver_stratum(r));
        if (snapshot_now) {
          const Sh9Rgb ref_sh = slot < reference->sh.size() ? reference->sh[slot] : Sh9Rgb{};
          const glm::dvec3 up(0.0, 0.0, 1.0);
          Snapshot::ReceiverLight l;
          l.planner_up = sh_irradiance(lr.sh, up);
          l.reference_up = sh_irradiance(ref_sh, up);
          l.planner_view = sh_irradiance(lr.sh, viewing.to_camera);
          l.reference_view = sh_irradiance(ref_sh, viewing.to_camera);
          l.de2000_view = ciede2000(display_lab(l.planner_view, settings.exposure),
                                    display_lab(l.reference_view, settings.exposure));
          l.viewed_pop = ev.viewed_pop && viewing.weight > 0.0;
          snapshot_light.push_back(l);
        }
        if (observe) {
          observed.receivers.push_back(
              {r.id, r.position, r.size_m, lr.sh,
               slot < reference->sh.size() ? reference->sh[slot] : Sh9Rgb{}, viewing.weight,
               ev.viewed_pop && viewing.weight > 0.0});
        }
        ++slot;
      }
      metrics.demand_point(lr, glm::length(r.position - mf.camera.position), DemandKind::receiver);
    }
    for (std::size_t k = 0; k < demand.size(); ++k) {
      metrics.demand_point(demand_lookups[k], demand[k].distance_m, demand[k].kind);
    }

    const PlannerStats stats = planner.stats();
    costs.live_probes = stats.live_probes;
    costs.bytes = stats.bytes;
    metrics.costs(costs);

    // 6. deliver what finished this frame.
    t0 = Clock::now();
    for (const auto& p : finished) planner.deliver(p);
    result.timing.planner_s += seconds_since(t0);

    if (options.keep_frames) result.camera_path.push_back(mf.camera.position);
    if (snapshot_now) {
      Snapshot snap;
      snap.frame = mf.frame.index;
      snap.time = mf.frame.time;
      snap.camera = mf.camera.position;
      planner.describe_nodes(snap.nodes);
      for (const auto& r : motion.receivers()) snap.receivers.push_back(r.position);
      // The light per receiver, when every receiver is scored (a sampled referee has no truth
      // for the others, and the views pair the two lists by position).
      if (snapshot_light.size() == snap.receivers.size()) snap.light = std::move(snapshot_light);
      result.snapshots.push_back(std::move(snap));
    }
    FrameRow row = metrics.end_frame();
    if (observe) {
      observed.frame = mf.frame.index;
      observed.time = mf.frame.time;
      observed.camera = mf.camera.position;
      observed.look = mf.look;
      observed.camera_cut = mf.camera.cut;
      observed.view = motion.view();
      observed.row = row;
      options.on_frame(observed);
    }
    if (options.keep_frames) result.frames.push_back(row);
    ++frame_index;
  }
  metrics.set_sample(scenario.reference.sample_stride, receivers_lit);
  result.summary = metrics.summary();
  result.timing.frames = static_cast<std::int64_t>(frame_index);
  result.timing.total_s = seconds_since(t_start);
  return result;
}

}  // namespace

RunResult simulate(const Scenario& scenario, const World& world, const ReferenceTrack& reference,
                   Planner& planner, const SimulationOptions& options) {
  return run_simulation(scenario, world, &reference, planner, options);
}

RunResult simulate_without_reference(const Scenario& scenario, const World& world, Planner& planner,
                                     const SimulationOptions& options) {
  return run_simulation(scenario, world, nullptr, planner, options);
}

}  // namespace ambisim
