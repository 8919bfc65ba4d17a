// The film shows what was scored: on a still scene the oracle's panel is the truth panel, a
// sphere's pixels are the displayed irradiance the planner gave it, a worse planner's panel is
// not the truth, a pop is ringed in the frames after it and nowhere else, and the frames
// sample the run at the film's rate.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "policies/registry/registry.h"
#include "sim/colour/tone_map.h"
#include "sim/run/reference_track.h"
#include "sim/run/simulator.h"
#include "sim/scenario/scenario.h"
#include "sim/world/world.h"
#include "viz/film.h"

namespace {

using namespace ambisim;

const std::string kStill = std::string(AMBISIM_SOURCE_DIR) + "/tests/data/film_still.json";
constexpr int kW = 320, kH = 180;
// Below the captions (font height / 24 of the panel plus its margin and background).
constexpr int kCaptionRows = 24;

struct StillRun {
  Scenario scenario = load_scenario(kStill);
  World world{scenario.world};
  std::shared_ptr<const ReferenceTrack> reference = compute_reference_track(scenario, world);

  FilmRun run(const std::string& planner_name, double* exposure) const {
    auto planner = make_planner(planner_name);
    FilmRun fr;
    fr.label = planner_name;
    SimulationOptions options;
    options.on_frame = [&](const FrameObservation& f) { fr.frames.push_back(f); };
    const RunResult result = simulate(scenario, world, *reference, *planner, options);
    *exposure = result.exposure;
    return fr;
  }
};

FilmSettings settings_for(const std::vector<FilmFrame>& frames, double exposure, double fov) {
  FilmSettings s;
  s.panel_width = kW;
  s.panel_height = kH;
  s.fov_deg = fov;
  s.exposure = exposure;
  for (const auto& f : frames) s.camera_positions.push_back(f.camera);
  return s;
}

// Mean and largest absolute difference of two panels of an image, below the captions.
std::pair<double, int> panel_difference(const ImageRgb8& img, int a, int b) {
  double sum = 0.0;
  int largest = 0;
  long n = 0;
  for (int y = kCaptionRows; y < img.height; ++y) {
    for (int x = 0; x < kW; ++x) {
      for (int c = 0; c < 3; ++c) {
        const int d = std::abs(img.pixel(a * kW + x, y)[c] - img.pixel(b * kW + x, y)[c]);
        sum += d;
        largest = std::max(largest, d);
        ++n;
      }
    }
  }
  return {sum / static_cast<double>(n), largest};
}

int red_pixels(const ImageRgb8& img, int panel) {
  int n = 0;
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < kW; ++x) {
      const std::uint8_t* p = img.pixel(panel * kW + x, y);
      if (p[0] == 255 && p[1] == 0 && p[2] == 0) ++n;
    }
  }
  return n;
}

}  // namespace

TEST_CASE("film: on a still scene the oracle's panel is the truth panel", "[viz][film]") {
  const StillRun still;
  double exposure = 0.0;
  const FilmRun oracle = still.run("oracle", &exposure);
  const FilmRun constant = still.run("constant", &exposure);
  REQUIRE(oracle.frames.size() == 30);
  const double fov = oracle.frames.front().view.fov_deg;
  const auto frames = compose_film({oracle, constant}, 0.0, 1.0, 10);
  REQUIRE(frames.size() == 10);
  REQUIRE(frames.front().panels.size() == 3);
  FilmRenderer renderer(still.world, settings_for(frames, exposure, fov), 3);
  const ImageRgb8 img = renderer.render(frames.back());
  REQUIRE(img.width == 3 * kW);
  REQUIRE(img.height == kH);

  // Stated tolerance: the oracle's panel equals the truth's within 1 level on average and 8
  // at any pixel (the same geometry and colours; only the captions differ, and they are cut).
  const auto [oracle_mean, oracle_max] = panel_difference(img, 0, 2);
  CHECK(oracle_mean <= 1.0);
  CHECK(oracle_max <= 8);
  // The one-capture constant planner lights the object otherwise: visibly not the truth.
  const auto [constant_mean, constant_max] = panel_difference(img, 1, 2);
  CHECK(constant_max > 20);
  CHECK(constant_mean > oracle_mean);

  // The centre of the camera object's sphere shows the displayed irradiance at the normal
  // facing the camera (within the vertex shading's interpolation).
  const FilmFrame& f = frames.back();
  const FilmSphere& s = f.panels[2].spheres.front();
  const ScreenCircle c = project_sphere(f.camera, f.look, fov, kW, kH, s.centre, s.radius_m);
  REQUIRE(c.visible);
  REQUIRE(c.radius > 10.0);
  const auto want = to_srgb8(sh_irradiance(s.sh, glm::normalize(f.camera - s.centre)), exposure);
  const std::uint8_t* got = img.pixel(2 * kW + static_cast<int>(c.x), static_cast<int>(c.y));
  for (int k = 0; k < 3; ++k) {
    INFO("channel " << k);
    CHECK(std::abs(int(got[k]) - int(want[static_cast<std::size_t>(k)])) <= 6);
  }
}

TEST_CASE("film: a pop is ringed in red from its frame for the ring time, in its panel only",
          "[viz][film]") {
  const StillRun still;
  double exposure = 0.0;
  FilmRun run = still.run("oracle", &exposure);
  REQUIRE(run.frames.size() == 30);
  // The oracle never pops; a synthetic pop of the camera object at frame 12 (t = 0.4 s).
  for (const auto& f : run.frames) {
    for (const auto& r : f.receivers) REQUIRE_FALSE(r.viewed_pop);
  }
  REQUIRE_FALSE(run.frames[12].receivers.empty());
  run.frames[12].receivers.front().viewed_pop = true;
  const double fov = run.frames.front().view.fov_deg;
  const auto frames = compose_film({run}, 0.0, 1.0, 30, 0.2);
  REQUIRE(frames.size() == 30);
  FilmRenderer renderer(still.world, settings_for(frames, exposure, fov), 2);
  for (int i : {11, 12, 15, 17, 20, 25}) {
    INFO("film frame " << i);
    const ImageRgb8 img = renderer.render(frames[static_cast<std::size_t>(i)]);
    const bool ringed = i >= 12 && i < 18;  // 0.4 s <= t < 0.4 + 0.2 s
    if (ringed) {
      CHECK(red_pixels(img, 0) > 100);
    } else {
      CHECK(red_pixels(img, 0) == 0);
    }
    CHECK(red_pixels(img, 1) == 0);  // the truth never pops
  }
}

TEST_CASE("film: frames sample the run at the film's rate", "[viz][film]") {
  const StillRun still;
  double exposure = 0.0;
  const FilmRun run = still.run("constant", &exposure);
  // The run is at 30 fps: a 12 fps film of 0.25..0.75 s has 6 frames, each showing the last
  // simulated frame at or before its time.
  const auto frames = compose_film({run}, 0.25, 0.75, 12);
  REQUIRE(frames.size() == 6);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const double t = 0.25 + static_cast<double>(i) / 12.0;
    INFO(i);
    CHECK(frames[i].time <= t + 1e-9);
    CHECK(frames[i].time > t - 1.0 / 30.0);
    CHECK(frames[i].panels.size() == 2);
    CHECK(frames[i].panels[0].caption.rfind("constant", 0) == 0);
  }
  CHECK_THROWS(compose_film({run}, 0.5, 0.5, 12));
}
