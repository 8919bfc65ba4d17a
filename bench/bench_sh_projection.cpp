// SH projection: the naive double-precision reference against the folded-table ShProjector,
// and the batched reference irradiance integrator. Radiance is seeded and hash-free random.
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

#include <glm/geometric.hpp>

#include "sim/sh/irradiance_reference.h"
#include "sim/sh/sh_projection.h"

namespace {

using ambisim::CubeMap;
using ambisim::Rgb;

CubeMap random_cube(int n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  CubeMap cube(n);
  // Radiance in [0, 4) from the top 24 bits: exact in float and independent of the library's
  // distribution implementation.
  auto next = [&] { return static_cast<float>(rng() >> 40) * (4.0f / 16777216.0f); };
  for (Rgb& t : cube.texel) t = Rgb(next(), next(), next());
  return cube;
}

void BM_ProjectNaive(benchmark::State& state) {
  const CubeMap cube = random_cube(static_cast<int>(state.range(0)), 1);
  for (auto _ : state) benchmark::DoNotOptimize(ambisim::project_cube_naive(cube));
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(cube.texel.size()));
}
BENCHMARK(BM_ProjectNaive)->Arg(16)->Arg(17);

void BM_ProjectFast(benchmark::State& state) {
  const CubeMap cube = random_cube(static_cast<int>(state.range(0)), 1);
  const ambisim::ShProjector& projector = ambisim::projector_for(cube.size);
  for (auto _ : state) benchmark::DoNotOptimize(projector.project(cube));
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(cube.texel.size()));
}
// 16: folded table; 17: odd size, dense Eigen product; 64: reference-capture size.
BENCHMARK(BM_ProjectFast)->Arg(16)->Arg(17)->Arg(64);

void BM_ProjectFace(benchmark::State& state) {
  const CubeMap cube = random_cube(16, 1);
  const ambisim::ShProjector& projector = ambisim::projector_for(16);
  for (auto _ : state) {
    ambisim::Sh9Rgb acc;
    projector.accumulate_face(cube, ambisim::CubeFace::PosZ, acc);
    benchmark::DoNotOptimize(acc);
  }
}
BENCHMARK(BM_ProjectFace);

std::vector<glm::dvec3> six_normals() {
  return {glm::dvec3(1, 0, 0),
          glm::dvec3(0, 0, 1),
          glm::dvec3(0, 0, -1),
          glm::normalize(glm::dvec3(1, 1, 1)),
          glm::normalize(glm::dvec3(-1, 2, 0.5)),
          glm::normalize(glm::dvec3(0.3, -0.2, -1))};
}

void BM_IrradianceIntegrator64(benchmark::State& state) {
  const CubeMap cube = random_cube(64, 2);
  const ambisim::IrradianceIntegrator integrator(64, six_normals());
  for (auto _ : state) benchmark::DoNotOptimize(integrator.integrate(cube));
}
BENCHMARK(BM_IrradianceIntegrator64)->Unit(benchmark::kMicrosecond);

void BM_IrradianceIntegratorBuild64(benchmark::State& state) {
  for (auto _ : state) {
    const ambisim::IrradianceIntegrator integrator(64, six_normals());
    benchmark::DoNotOptimize(&integrator);
  }
}
BENCHMARK(BM_IrradianceIntegratorBuild64)->Unit(benchmark::kMillisecond);

void BM_ExactIrradianceSingle64(benchmark::State& state) {
  const CubeMap cube = random_cube(64, 2);
  const auto normals = six_normals();
  for (auto _ : state) {
    for (const auto& n : normals) benchmark::DoNotOptimize(ambisim::exact_irradiance(cube, n));
  }
}
BENCHMARK(BM_ExactIrradianceSingle64)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
