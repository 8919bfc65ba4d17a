// Capture cost on the default 4 km world: the max-mip pyramid marcher against the naive
// fixed-step reference, 16x16 per face, at three kinds of place; plus world generation.
#include <benchmark/benchmark.h>

#include <glm/geometric.hpp>

#include "sim/render/capture.h"
#include "sim/world/landmarks.h"
#include "sim/world/world.h"

using namespace ambisim;

namespace {

const World& default_world() {
  static const World w{WorldParams{}};
  return w;
}

// 0: on the road (1.5 m above the asphalt, at the deepest cutting), 1: 10 m in front of
// the forest-edge landmark, 2: in the air, 150 m above the terrain near the map centre.
glm::dvec3 place(int which) {
  const World& w = default_world();
  static const WorldLandmarks l = find_landmarks(w);
  switch (which) {
    case 0:
      return l.deepest_cutting.point + glm::dvec3(0.0, 0.0, 1.5);
    case 1: {
      const glm::dvec2 p = glm::dvec2(l.forest_edge.edge) - l.forest_edge.direction * 10.0;
      return {p.x, p.y, w.ground_height(p.x, p.y) + 2.0};
    }
    default: {
      const glm::dvec2 c = 0.5 * (w.min_xy() + w.max_xy());
      return {c.x, c.y, w.surface_height(c.x, c.y) + 150.0};
    }
  }
}

const char* kPlaceNames[] = {"road", "forest_edge", "air"};

void BM_Capture16(benchmark::State& state) {
  const World& w = default_world();
  const glm::dvec3 p = place(static_cast<int>(state.range(0)));
  const Marcher m = state.range(1) == 0 ? Marcher::accelerated : Marcher::naive;
  state.SetLabel(std::string(kPlaceNames[state.range(0)]) +
                 (m == Marcher::accelerated ? " accelerated" : " naive"));
  for (auto _ : state) {
    CubeMap c = capture(w, p, 16, m);
    benchmark::DoNotOptimize(c.texel.data());
  }
}
BENCHMARK(BM_Capture16)->ArgsProduct({{0, 1, 2}, {0, 1}})->Unit(benchmark::kMillisecond);

void BM_GenerateDefaultWorld(benchmark::State& state) {
  for (auto _ : state) {
    World w{WorldParams{}};
    benchmark::DoNotOptimize(w.max_surface());
  }
}
BENCHMARK(BM_GenerateDefaultWorld)->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace

BENCHMARK_MAIN();
