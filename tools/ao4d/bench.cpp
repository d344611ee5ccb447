// AO throughput: rays per second on the built-in shapes at 10^4 to 10^5 cells, and the time of a
// 50^3 volume. Run from the release build, e.g.
//   build/release/tools/ao4d/ao4d_bench --benchmark_counters_tabular=true
#include "ao4d/render.hpp"
#include "ao4d/scene.hpp"
#include "ao4d/shapes.hpp"

#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <string>
#include <utility>

namespace {

// Meshes are built once per (shape, grid); marching is not what is measured.
const ao4d::Scene& scene_for(const std::string& shape, int grid) {
  static std::map<std::pair<std::string, int>, std::unique_ptr<ao4d::Scene>> cache;
  auto& slot = cache[{shape, grid}];
  if (!slot) slot = std::make_unique<ao4d::Scene>(ao4d::make_shape(shape, grid));
  return *slot;
}

// AO at the mesh's vertices along their normals: every AO ray is a real occlusion query.
void BM_VertexAo(benchmark::State& state, const std::string& shape) {
  const ao4d::Scene& scene = scene_for(shape, static_cast<int>(state.range(0)));
  ao4d::AoParams params;
  params.radius = 0.25 * scene.diagonal();
  params.rays = 64;
  params.threads = 2;
  std::size_t rays = 0;
  for (auto _ : state) {
    const auto ao = ao4d::vertex_ambient_occlusion(scene, params);
    benchmark::DoNotOptimize(ao.data());
    rays += ao.size() * static_cast<std::size_t>(params.rays);
  }
  state.counters["cells"] = static_cast<double>(scene.mesh().cells.size());
  state.counters["rays/s"] = benchmark::Counter(static_cast<double>(rays), benchmark::Counter::kIsRate);
}

void BM_Volume50(benchmark::State& state, const std::string& shape) {
  const ao4d::Scene& scene = scene_for(shape, static_cast<int>(state.range(0)));
  ao4d::AoParams params;
  params.radius = 0.25 * scene.diagonal();
  params.rays = 128;
  params.threads = 2;
  ao4d::CameraParams camera;
  camera.size = 50;
  for (auto _ : state) {
    const auto volume = ao4d::render_volume(scene, camera, params);
    benchmark::DoNotOptimize(volume.ao.data());
  }
  state.counters["cells"] = static_cast<double>(scene.mesh().cells.size());
}

}  // namespace

int main(int argc, char** argv) {
  // Grids chosen so the shapes span about 10^4 to 10^5 cells (the "cells" counter reports them).
  const std::pair<const char*, std::pair<int, int>> shapes[] = {{"hypersphere", {6, 10}},
                                                                {"tesseract", {6, 9}},
                                                                {"indented-tesseract", {6, 9}},
                                                                {"duocylinder", {6, 10}},
                                                                {"torus", {8, 14}}};
  for (const auto& [name, grids] : shapes) {
    const std::string shape = name;
    benchmark::RegisterBenchmark(("vertex_ao/" + shape).c_str(), BM_VertexAo, shape)
        ->Arg(grids.first)
        ->Arg(grids.second)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
    benchmark::RegisterBenchmark(("volume50/" + shape).c_str(), BM_Volume50, shape)
        ->Arg(grids.second)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
