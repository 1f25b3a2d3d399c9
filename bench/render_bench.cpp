// Time to draw one frame with the software renderer: image sizes x flag grids x threads, and
// each shading mode at 1280 x 720.
//
//   build/bench/render_bench [--benchmark_filter=...]
#include <benchmark/benchmark.h>

#include "bench/flag_pose.hpp"
#include "server/render/renderer.hpp"

namespace flagsim {
namespace {

void BM_Render(benchmark::State& bench) {
  const int width = int(bench.range(0)), height = int(bench.range(1));
  const int cols = int(bench.range(2)), rows = int(bench.range(3));
  const render::RenderScene scene = bench::BenchScene(cols, rows);
  render::Camera camera;
  camera.width = width;
  camera.height = height;
  render::RenderOptions options;
  options.threads = int(bench.range(4));
  options.mode = render::ShadingMode(bench.range(5));
  render::Renderer renderer;
  render::Framebuffer framebuffer;
  renderer.Render(scene, camera, options, &framebuffer);
  for (auto _ : bench) renderer.Render(scene, camera, options, &framebuffer);
  bench.counters["triangles"] = double(renderer.triangles_drawn());
}

void Sizes(benchmark::internal::Benchmark* b) {
  const int gouraud = int(render::ShadingMode::kGouraud);
  for (const auto& [w, h] : {std::pair{640, 480}, std::pair{1280, 720}, std::pair{1920, 1080}}) {
    for (const auto& [c, r] : {std::pair{32, 24}, std::pair{64, 48}, std::pair{128, 96}}) {
      for (const int threads : {1, 2}) b->Args({w, h, c, r, threads, gouraud});
    }
  }
  for (int mode = 0; mode < 4; ++mode) b->Args({1280, 720, 64, 48, 2, mode});
}

BENCHMARK(BM_Render)
    ->ArgNames({"w", "h", "cols", "rows", "threads", "mode"})
    ->Apply(Sizes)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace flagsim

BENCHMARK_MAIN();
