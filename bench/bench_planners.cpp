// Planner cost against the number of live probes: lookup (random points near the camera) at
// 1e3, 1e4 and 1e5 live probes, and the planner's per-frame work at 1e3 and 1e4, for every
// planner with a structure (constant, hemisphere and oracle have none: skipped).
//
// No rendering: a driver flies the camera over the default 4 km world and delivers every capture
// a planner starts with synthetic coefficients (a smooth function of position). It calls the
// planner in the simulator's order (sim/run/simulator.cpp): set_receivers, plan, started/refused,
// update, deliver. To reach N live probes a planner gets parameters that let it hold N (no
// expiry, caps at N, a grid of N points) and a large budget (256 captures per frame, delivered
// the next frame) while the camera sweeps the map in lanes 40 m apart at 3 m per frame
// (180 m/s; the camera-centred grid fills standing still). A fill stops at N, when the planner
// has not grown for 3000 frames (it holds no more), or after a wall-time limit (90 s; 300 s
// for `nearest` and 180 s for the octrees, whose fills are quadratic); the counters say how many
// probes it actually held
// (`live`), how long the fill took (`fill_s`), and the bytes per live probe
// (PlannerStats::bytes / live_probes, structure included).
//
// lookup benchmarks: one lookup() per iteration over 4096 fixed points (seed 7) uniform in a
//   50 m disc around the camera, 0.5-5 m above the ground (per_object: its receivers' positions,
//   where its lookups are exact).
// frame benchmarks: one simulated frame per iteration at the thesis' budget (1 face per frame:
//   one capture in flight at a time, usable 6 frames after its start), the camera driving on at
//   30 m/s: plan + started + update + deliver, with update() alone as the counter `update_us`.
//   The planner keeps its state across iterations; `live` is the count at the end.
// BM_MemoryL1fp16: bytes per live probe at 1e4 with order=L1, precision=fp16 (24-byte sets).
//
//   build-perf/bench/bench_planners --benchmark_out=planners.json --benchmark_out_format=json
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <deque>
#include <limits>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "policies/ambisim/demand_planner.h"
#include "policies/registry/registry.h"
#include "policies/thesis/shgraph.h"
#include "policies/thesis/shgraph2d.h"
#include "sim/world/spline.h"
#include "sim/world/world.h"
#include "sim/world/world_queries.h"

using namespace ambisim;

namespace {

constexpr double kFps = 60.0;
constexpr double kFillStepM = 3.0;      // camera advance per frame while filling
constexpr double kDriveStepM = 0.5;     // 30 m/s at 60 fps while measuring frames
constexpr double kLaneSpacingM = 40.0;  // lanes of the sweep, wider than a planner's region
constexpr double kCameraHeightM = 2.0;
constexpr int kFillCaptures = 256;     // captures startable per frame while filling
constexpr int kSettleFrames = 180;     // 3 s standing still after the fill
constexpr double kFillBudgetS = 90.0;  // wall-time limit of one fill
constexpr int kLookupPoints = 4096;

const World& world() {
  static const World w{WorldParams{}};
  return w;
}

const WorldQueries& queries() {
  static const WorldQueries q = planner_world_queries(world());
  return q;
}

// Synthetic coefficients: smooth in position (so interpolation has something to do), all
// channels positive.
Sh9Rgb synthetic_sh(const glm::dvec3& p) {
  Sh9Rgb sh;
  for (int i = 0; i < kShCount; ++i) {
    const double a = 0.3 + 0.2 * std::sin(p.x / 37.0 + i) * std::cos(p.y / 53.0 - i);
    sh.c[static_cast<std::size_t>(i)] =
        Rgb(static_cast<float>(a), static_cast<float>(0.8 * a), static_cast<float>(0.6 * a + 0.05));
  }
  return sh;
}

// A boustrophedon over the map: lanes along x, kLaneSpacingM apart, at kCameraHeightM above the
// surface. Distance s along the path gives position and direction.
struct LanePath {
  glm::dvec2 lo, hi;
  LanePath() {
    const glm::dvec2 margin(150.0);
    lo = world().min_xy() + margin;
    hi = world().max_xy() - margin;
  }
  glm::dvec3 at(double s, glm::dvec3* velocity_dir) const {
    const double lane_len = hi.x - lo.x;
    const auto lanes = static_cast<std::int64_t>(std::floor((hi.y - lo.y) / kLaneSpacingM));
    auto lane = static_cast<std::int64_t>(std::floor(s / lane_len));
    const double t = s - static_cast<double>(lane) * lane_len;
    lane %= std::max<std::int64_t>(lanes, 1);
    const bool forward = lane % 2 == 0;
    const double x = forward ? lo.x + t : hi.x - t;
    const double y = lo.y + static_cast<double>(lane) * kLaneSpacingM;
    if (velocity_dir) *velocity_dir = glm::dvec3(forward ? 1.0 : -1.0, 0.0, 0.0);
    return {x, y, world().surface_height(x, y) + kCameraHeightM};
  }
};

struct Setup {
  std::string planner;
  std::string label;  // how it was made to hold N probes
  std::vector<std::string> params;
  int receivers = 8;                    // receivers kept around the camera (per_object: N)
  double fill_step_m = kFillStepM;      // camera advance per fill frame
  double fill_budget_s = kFillBudgetS;  // wall-time limit of the fill
};

// Parameters that let `planner` hold n live probes.
Setup setup_for(const std::string& planner, std::int64_t n) {
  const std::string ns = std::to_string(n);
  Setup s{planner, "", {}, 8};
  if (planner == "nearest") {
    s.params = {"max_probes=" + ns, "spacing_m=2", "lifetime_s=1e9"};
    // One capture per frame at most, and every frame scans every probe: the fill to 1e5 is
    // quadratic (about 3 minutes).
    s.fill_budget_s = 300.0;
  } else if (planner == "per_object") {
    s.receivers = static_cast<int>(n);
    s.params = {"lifetime_s=1e9", "move_m=1e9"};
    s.label = "one receiver per probe";
  } else if (planner == "grid") {
    // nz = 4 layers, nx = ny = sqrt(n / 4) (rounded up; layers under the ground are dropped).
    const auto side = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n) / 4.0)));
    s.params = {"nx=" + std::to_string(side), "ny=" + std::to_string(side), "nz=4"};
    s.fill_step_m = 0.0;  // camera-centred: it fills standing still (moving, it scrolls away)
  } else if (planner == "cascades") {
    // As grid, over its 4 levels: nz = 4 layers, nx = ny = sqrt(n / 16) (rounded up).
    const auto side = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n) / 16.0)));
    s.params = {"levels=4", "nx=" + std::to_string(side), "ny=" + std::to_string(side), "nz=4"};
    s.fill_step_m = 0.0;
  } else if (planner.rfind("octree", 0) == 0) {
    s.params = {"retention=lifetime", "lifetime_s=1e9"};
    s.fill_budget_s = 180.0;  // every frame expires over every set: the fill is quadratic
  } else if (planner.rfind("shgraph", 0) == 0) {
    s.params = {"lifetime_s=1e9", "widen_cells=5"};
  } else if (planner == "ambisim") {
    s.params = {"max_probes=" + ns, "lifetime_s=1e9", "spacing_per_m=0", "min_spacing_m=3",
                "max_distance_m=1000"};
  }
  return s;
}

// Drives one planner frame by frame, delivering synthetic probes.
class Driver {
 public:
  explicit Driver(const Setup& s) : setup_(s) {
    planner_ = make_planner(s.planner, planner_params_from_cli(s.planner, s.params));
  }

  Planner& planner() { return *planner_; }
  const glm::dvec3& camera() const { return camera_; }
  const std::vector<Planner::ReceiverView>& receivers() const { return receivers_; }

  // One frame: camera advances `step_m`; at most `startable` captures start, each usable
  // `latency` frames later. Returns the seconds spent in update().
  double frame(double step_m, int startable, double faces_per_frame, int latency) {
    s_ += step_m;
    glm::dvec3 dir;
    camera_ = path_.at(s_, &dir);
    FrameContext ctx;
    ctx.frame = frame_;
    ctx.time = static_cast<double>(frame_) / kFps;
    ctx.dt = 1.0 / kFps;
    ctx.camera_position = camera_;
    ctx.camera_velocity = dir * (step_m * kFps);
    ctx.camera_cut = frame_ == 0;
    ctx.faces_per_frame = faces_per_frame;
    ctx.face_size = 16;
    ctx.world = &queries();
    int owed = 0;
    for (const auto& f : flight_) owed += f.due > frame_ ? 1 : 0;
    ctx.startable_captures = std::max(0, startable - owed);
    place_receivers();
    planner_->set_receivers(receivers_);
    const auto requests = planner_->plan(ctx);
    int started = 0;
    for (const auto& r : requests) {
      if (started < ctx.startable_captures) {
        planner_->started(r.tag);
        flight_.push_back({r, ctx.time, frame_ + latency});
        ++started;
      } else {
        planner_->refused(r.tag);
      }
    }
    const auto t0 = std::chrono::steady_clock::now();
    planner_->update(ctx);
    const double update_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    while (!flight_.empty() && flight_.front().due <= frame_) {
      const InFlight& f = flight_.front();
      FinishedProbe p;
      p.tag = f.request.tag;
      p.position = f.request.position;
      p.sh = synthetic_sh(f.request.position);
      p.requested_time = f.requested_time;
      p.finished_time = ctx.time;
      planner_->deliver(p);
      flight_.pop_front();
    }
    ++frame_;
    return update_s;
  }

  // Fills to n live probes (see the file comment). Returns the wall time taken.
  // Fills to n live probes at a burst of captures, then lets the captures in flight land and,
  // with `settle`, stands kSettleFrames more: every fade and SHGraph's pattern blend (1 s by
  // default) has run its course, so lookups and frames measure the structure as it stands
  // between bursts. Without it they measure it right after one (sets a frame or two old).
  double fill(std::int64_t n, bool settle) {
    const auto t0 = std::chrono::steady_clock::now();
    std::int64_t best = 0;
    std::int64_t since_growth = 0;
    for (;;) {
      frame(setup_.fill_step_m, kFillCaptures, 6.0 * kFillCaptures, 1);
      const std::int64_t live = planner_->stats().live_probes;
      if (live >= n) break;
      if (live > best) {
        best = live;
        since_growth = 0;
      } else if (++since_growth > 3000) {
        break;  // it does not grow any more: this is as many as it holds
      }
      if (std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() >
          setup_.fill_budget_s) {
        break;
      }
    }
    // Let the captures in flight land (the camera stands, nothing new starts), then settle.
    const int still = settle ? 2 + kSettleFrames : 2;
    for (int i = 0; i < still; ++i) frame(0.0, 0, 6.0 * kFillCaptures, 1);
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }

 private:
  struct InFlight {
    CaptureRequest request;
    double requested_time;
    std::int64_t due;
  };

  // Receivers: `setup_.receivers` static objects on the ground within 60 m of the camera,
  // replaced by new ones (new ids, as traffic would be) whenever the camera has moved 60 m.
  // per_object's N receivers are placed once, at the start: it holds one probe per receiver.
  void place_receivers() {
    const auto n = static_cast<std::size_t>(setup_.receivers);
    if (!receivers_.empty() &&
        (setup_.planner == "per_object" || glm::distance(camera_, receivers_anchor_) < 60.0)) {
      return;
    }
    receivers_anchor_ = camera_;
    receivers_.clear();
    std::mt19937_64 rng(static_cast<std::uint64_t>(next_receiver_id_) * 7919u + 3u);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (std::size_t i = 0; i < n; ++i) {
      double x, y;
      do {
        x = u(rng);
        y = u(rng);
      } while (x * x + y * y > 1.0);
      const double px = camera_.x + 60.0 * x, py = camera_.y + 60.0 * y;
      receivers_.push_back(
          {next_receiver_id_++, {px, py, world().surface_height(px, py) + 1.0}, glm::dvec3(0.0)});
    }
  }

  Setup setup_;
  std::unique_ptr<Planner> planner_;
  LanePath path_;
  double s_ = 0.0;
  std::int64_t frame_ = 0;
  glm::dvec3 camera_{0.0};
  std::deque<InFlight> flight_;
  std::vector<Planner::ReceiverView> receivers_;
  glm::dvec3 receivers_anchor_{0.0};
  std::uint64_t next_receiver_id_ = 1;
};

// One filled planner at a time (a 1e5-probe structure can be hundreds of MB).
struct Filled {
  std::string key;
  std::unique_ptr<Driver> driver;
  double fill_s = 0.0;
  std::vector<glm::dvec3> points;
};

// `extra`: parameters added to the setup's (the compact-format memory benchmark); `receivers`:
// objects kept around the camera instead of the setup's (the game's-load frame benchmark).
// `points`: lookup points (kLookupPoints by default; a batch of one frame's receivers).
// `settle`: as Driver::fill.
Filled& filled(const std::string& planner, std::int64_t n,
               const std::vector<std::string>& extra = {}, int receivers = 0,
               int points = kLookupPoints, bool settle = true) {
  static Filled f;
  std::string key = planner + "/" + std::to_string(n) + "/r" + std::to_string(receivers) + "/p" +
                    std::to_string(points) + (settle ? "/settled" : "/fresh");
  for (const auto& e : extra) key += "/" + e;
  if (f.key == key) return f;
  f.driver.reset();
  f.key = key;
  Setup s = setup_for(planner, n);
  s.params.insert(s.params.end(), extra.begin(), extra.end());
  if (receivers > 0) s.receivers = receivers;
  f.driver = std::make_unique<Driver>(s);
  f.fill_s = f.driver->fill(n, settle);
  f.points.clear();
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0), h(0.5, 5.0);
  const glm::dvec3 c = f.driver->camera();
  const auto& rec = f.driver->receivers();
  for (int i = 0; i < points; ++i) {
    if (planner == "per_object") {
      f.points.push_back(rec[static_cast<std::size_t>(rng() % rec.size())].position);
      continue;
    }
    double x, y;
    do {
      x = u(rng);
      y = u(rng);
    } while (x * x + y * y > 1.0);
    const double px = c.x + 50.0 * x, py = c.y + 50.0 * y;
    f.points.push_back({px, py, world().ground_height(px, py) + h(rng)});
  }
  return f;
}

void report_stats(benchmark::State& state, Planner& p, std::int64_t target, double fill_s) {
  const PlannerStats st = p.stats();
  state.counters["target"] = static_cast<double>(target);
  state.counters["live"] = static_cast<double>(st.live_probes);
  state.counters["nodes"] = static_cast<double>(st.nodes);
  state.counters["bytes_per_probe"] =
      st.live_probes > 0 ? static_cast<double>(st.bytes) / static_cast<double>(st.live_probes)
                         : 0.0;
  state.counters["fill_s"] = fill_s;
}

// The SHGraph planners keep their straightforward code paths as a reference
// (ShGraphCore::set_naive): BM_LookupShGraphNaive and BM_FrameShGraphNaive time those on the
// same filled structure.
void set_naive(Planner& p, bool naive) {
  if (auto* g = dynamic_cast<ShGraphPlanner*>(&p)) g->set_naive(naive);
  if (auto* g = dynamic_cast<ShGraph2dPlanner*>(&p)) g->set_naive(naive);
}

bool has_naive_paths(const std::string& planner) { return planner.rfind("shgraph", 0) == 0; }
// ambisim's naive lookup is its linear scan (DemandPlanner::lookup_reference) on the same
// probes; it has no naive frame path.
bool has_naive_lookup(const std::string& planner) {
  return has_naive_paths(planner) || planner == "ambisim";
}

LookupResult lookup_by(const Planner& p, const glm::dvec3& q, bool naive) {
  if (naive) {
    if (const auto* a = dynamic_cast<const DemandPlanner*>(&p)) return a->lookup_reference(q);
  }
  return p.lookup(q);
}

// `settle = false` (BM_LookupFresh): right after the fill's last burst of captures.
void BM_Lookup(benchmark::State& state, const std::string& planner, bool naive, bool settle) {
  const std::int64_t n = state.range(0);
  Filled& f = filled(planner, n, {}, 0, kLookupPoints, settle);
  Planner& p = f.driver->planner();
  set_naive(p, naive);
  std::size_t i = 0;
  int fell_back = 0;
  for (auto _ : state) {
    const LookupResult r = lookup_by(p, f.points[i], naive);
    benchmark::DoNotOptimize(r);
    fell_back += r.fell_back ? 1 : 0;
    i = (i + 1) % f.points.size();
  }
  report_stats(state, p, n, f.fill_s);
  state.counters["fell_back"] = static_cast<double>(fell_back) /
                                static_cast<double>(std::max<std::int64_t>(1, state.iterations()));
  if (const auto* a = dynamic_cast<const DemandPlanner*>(&p)) {
    // ambisim's profile: the share of the points whose lookup mixes in the far field.
    int far = 0;
    for (const auto& q : f.points) far += a->lookup_uses_far_field(q) ? 1 : 0;
    state.counters["far_share"] = static_cast<double>(far) / static_cast<double>(f.points.size());
  }
  state.SetLabel(setup_for(planner, n).label);
  set_naive(p, false);
}

void BM_Frame(benchmark::State& state, const std::string& planner, bool naive) {
  const std::int64_t n = state.range(0);
  Filled& f = filled(planner, n);
  Driver& d = *f.driver;
  set_naive(d.planner(), naive);
  double update_s = 0.0;
  for (auto _ : state) update_s += d.frame(kDriveStepM, 1, 1.0, 6);
  report_stats(state, d.planner(), n, f.fill_s);
  state.counters["update_us"] =
      1e6 * update_s / static_cast<double>(std::max<std::int64_t>(1, state.iterations()));
  state.SetLabel(setup_for(planner, n).label);
  set_naive(d.planner(), false);
}

// ambisim near its probes: 4096 points within 1 m of its live probes (seed 9), where the bumps
// answer almost alone (far_share in the counters), on the same filled planner as BM_Lookup.
void BM_LookupNearProbes(benchmark::State& state, const std::string& planner) {
  const std::int64_t n = state.range(0);
  Filled& f = filled(planner, n);
  Planner& p = f.driver->planner();
  std::vector<ProbeNodeView> nodes;
  p.describe_nodes(nodes);
  std::vector<glm::dvec3> points;
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < kLookupPoints && !nodes.empty(); ++i) {
    const auto& node = nodes[static_cast<std::size_t>(rng() % nodes.size())];
    points.push_back(node.centre + glm::dvec3(u(rng), u(rng), u(rng)) / std::sqrt(3.0));
  }
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(p.lookup(points[i]));
    i = (i + 1) % points.size();
  }
  report_stats(state, p, n, f.fill_s);
  if (const auto* a = dynamic_cast<const DemandPlanner*>(&p)) {
    int far = 0;
    for (const auto& q : points) far += a->lookup_uses_far_field(q) ? 1 : 0;
    state.counters["far_share"] = static_cast<double>(far) / static_cast<double>(points.size());
  }
}

// A game's frame of lookups: every one of kBatchReceivers points (uniform in the 50 m disc
// around the camera, as BM_Lookup's) through Planner::lookup_many at n live probes; naive: one
// lookup_reference per point. The time per iteration is one frame's lookups.
constexpr int kBatchReceivers = 10000;

void BM_LookupMany(benchmark::State& state, const std::string& planner, bool naive) {
  const std::int64_t n = state.range(0);
  Filled& f = filled(planner, n, {}, 0, kBatchReceivers);
  Planner& p = f.driver->planner();
  LookupPoints batch;
  for (const auto& q : f.points) batch.push_back(q);
  std::vector<LookupResult> out;
  for (auto _ : state) {
    if (naive) {
      out.resize(batch.size());
      for (std::size_t i = 0; i < batch.size(); ++i) out[i] = lookup_by(p, batch.at(i), true);
    } else {
      p.lookup_many(batch, out);
    }
    benchmark::DoNotOptimize(out.data());
  }
  report_stats(state, p, n, f.fill_s);
  state.counters["receivers"] = static_cast<double>(batch.size());
}

// A game's frame of planner work: as BM_Frame, with kFrameReceivers objects around the camera
// (replaced by new ones every 60 m, as traffic would be) instead of 8.
constexpr int kFrameReceivers = 1000;

void BM_FrameReceivers(benchmark::State& state, const std::string& planner) {
  const std::int64_t n = state.range(0);
  Filled& f = filled(planner, n, {}, kFrameReceivers);
  Driver& d = *f.driver;
  double update_s = 0.0;
  for (auto _ : state) update_s += d.frame(kDriveStepM, 1, 1.0, 6);
  report_stats(state, d.planner(), n, f.fill_s);
  state.counters["receivers"] = static_cast<double>(d.receivers().size());
  state.counters["update_us"] =
      1e6 * update_s / static_cast<double>(std::max<std::int64_t>(1, state.iterations()));
}

// The naive baseline: the nearest of n probes by a linear scan (probes on a 4 m spacing,
// uniform in a square, queries uniform in it), returning its coefficients.
void BM_LookupNaive(benchmark::State& state) {
  const std::int64_t n = state.range(0);
  const double side = 4.0 * std::sqrt(static_cast<double>(n));
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0.0, side);
  struct Probe {
    glm::dvec3 position;
    Sh9Rgb sh;
  };
  std::vector<Probe> probes;
  for (std::int64_t i = 0; i < n; ++i) {
    const glm::dvec3 p(u(rng), u(rng), 2.0);
    probes.push_back({p, synthetic_sh(p)});
  }
  std::vector<glm::dvec3> points;
  for (int i = 0; i < kLookupPoints; ++i) points.emplace_back(u(rng), u(rng), 2.0);
  std::size_t i = 0;
  for (auto _ : state) {
    const glm::dvec3& q = points[i];
    std::size_t best = 0;
    double best_d2 = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < probes.size(); ++k) {
      const glm::dvec3 d = probes[k].position - q;
      const double d2 = glm::dot(d, d);
      if (d2 < best_d2) {
        best_d2 = d2;
        best = k;
      }
    }
    LookupResult r;
    r.sh = probes[best].sh;
    r.spacing_m = std::sqrt(best_d2);
    benchmark::DoNotOptimize(r);
    i = (i + 1) % points.size();
  }
  state.counters["live"] = static_cast<double>(n);
}

// What `+route` prediction costs per call: Spline3::closest_s of the default world's road
// (sim/world/spline.h) at points within 15 m of it. ShGraph and octree planners call it in plan()
// and update(), so every frame. With `reference`, the coarse samples are scanned one by one
// (closest_s_reference, the same answer) instead of searched in their tree.
void BM_RoadClosestS(benchmark::State& state, bool reference) {
  const Spline3& road = world().road();
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, road.length()), off(-15.0, 15.0);
  std::vector<glm::dvec3> points;
  for (int i = 0; i < kLookupPoints; ++i) {
    points.push_back(road.at(u(rng)) + glm::dvec3(off(rng), off(rng), 0.0));
  }
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(reference ? road.closest_s_reference(points[i])
                                       : road.closest_s(points[i]));
    i = (i + 1) % points.size();
  }
  state.counters["road_m"] = road.length();
}

// Memory per live probe with the most compact coefficient format (order=L1, precision=fp16:
// 24 bytes per set instead of 108), at 1e4 live probes: what the structure itself costs.
void BM_MemoryL1fp16(benchmark::State& state, const std::string& planner) {
  const std::int64_t n = state.range(0);
  Filled& f = filled(planner, n, {"order=L1", "precision=fp16"});
  for (auto _ : state) benchmark::DoNotOptimize(f.driver->planner().stats());
  report_stats(state, f.driver->planner(), n, f.fill_s);
}

// Planners with a structure to measure; constant, hemisphere and oracle hold no structure.
// What a vehicle's lane point pays to turn arc length into the curve's parameter, about 9 times
// per vehicle per frame (sim/world/terrain_queries.h): the first arc-length sample beyond s from
// its bucket, against the binary search over the road's samples (`reference`).
void BM_RoadFirstSampleAfter(benchmark::State& state, bool reference) {
  const Spline3& road = world().road();
  std::mt19937_64 rng(6);
  std::uniform_real_distribution<double> u(0.0, road.length());
  std::vector<double> arc(4096);
  for (double& s : arc) s = u(rng);
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(reference ? road.first_sample_after_reference(arc[i])
                                       : road.first_sample_after(arc[i]));
    i = (i + 1) % arc.size();
  }
  state.counters["samples"] = static_cast<double>(road.sample_arc_lengths().size());
}

const char* const kPlanners[] = {"nearest",       "per_object", "grid",    "cascades",
                                 "octree",        "octree+vp",  "shgraph", "shgraph+vp",
                                 "shgraph+route", "shgraph2d",  "ambisim"};

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RegisterBenchmark("BM_RoadClosestS", BM_RoadClosestS, false)
      ->Unit(benchmark::kMicrosecond);
  benchmark::RegisterBenchmark("BM_RoadClosestSReference", BM_RoadClosestS, true)
      ->Unit(benchmark::kMicrosecond);
  benchmark::RegisterBenchmark("BM_RoadFirstSampleAfter", BM_RoadFirstSampleAfter, false)
      ->Unit(benchmark::kNanosecond);
  benchmark::RegisterBenchmark("BM_RoadFirstSampleAfterReference", BM_RoadFirstSampleAfter, true)
      ->Unit(benchmark::kNanosecond);
  benchmark::RegisterBenchmark("BM_LookupNaive", BM_LookupNaive)
      ->Arg(1000)
      ->Arg(10000)
      ->Arg(100000)
      ->Unit(benchmark::kNanosecond);
  for (const char* name : kPlanners) {
    const std::string planner = name;
    // Registered per size so that one filled planner serves its lookup and frame benchmarks.
    for (const std::int64_t n : {1000, 10000, 100000}) {
      // Lookups first (fast, then naive on the same structure), then frames, which move on.
      for (const bool naive : {false, true}) {
        if (naive && !has_naive_lookup(planner)) continue;
        const std::string suffix =
            !naive ? "/" : (planner == "ambisim" ? "Reference/" : "ShGraphNaive/");
        benchmark::RegisterBenchmark(("BM_Lookup" + suffix + planner).c_str(), BM_Lookup, planner,
                                     naive, true)
            ->Arg(n)
            ->Unit(benchmark::kNanosecond);
      }
      for (const bool naive : {false, true}) {
        if (n > 10000 || (naive && !has_naive_paths(planner))) continue;
        const std::string suffix = naive ? "ShGraphNaive/" : "/";
        benchmark::RegisterBenchmark(("BM_Frame" + suffix + planner).c_str(), BM_Frame, planner,
                                     naive)
            ->Arg(n)
            ->Iterations(600)
            ->Unit(benchmark::kMicrosecond);
      }
      if (planner == "ambisim") {
        benchmark::RegisterBenchmark(("BM_LookupNearProbes/" + planner).c_str(),
                                     BM_LookupNearProbes, planner)
            ->Arg(n)
            ->Unit(benchmark::kNanosecond);
      }
      if (planner == "ambisim" && n == 10000) {
        for (const bool naive : {false, true}) {
          benchmark::RegisterBenchmark(
              (std::string(naive ? "BM_LookupManyReference/" : "BM_LookupMany/") + planner).c_str(),
              BM_LookupMany, planner, naive)
              ->Arg(n)
              ->Iterations(naive ? 1 : 3)
              ->Unit(benchmark::kMillisecond);
        }
      }
      if (planner == "ambisim" && n == 1000) {
        benchmark::RegisterBenchmark(("BM_FrameReceivers/" + planner).c_str(), BM_FrameReceivers,
                                     planner)
            ->Arg(n)
            ->Iterations(600)
            ->Unit(benchmark::kMicrosecond);
      }
      if (n == 10000 && planner != "nearest") {  // nearest stores L2/fp32 only
        benchmark::RegisterBenchmark(("BM_MemoryL1fp16/" + planner).c_str(), BM_MemoryL1fp16,
                                     planner)
            ->Arg(n)
            ->Iterations(1);
      }
      if (n == 10000) {
        // Last of its size: it fills again, without the settling.
        benchmark::RegisterBenchmark(("BM_LookupFresh/" + planner).c_str(), BM_Lookup, planner,
                                     false, false)
            ->Arg(n)
            ->Unit(benchmark::kNanosecond);
      }
    }
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
