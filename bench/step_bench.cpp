// One physics step of the flag at several grid sizes, reported as nanoseconds per node-step
// (one substep of one node: the unit the integrators are compared in).
//
//   build/bench/step_bench [--benchmark_filter=...]
#include <benchmark/benchmark.h>

#include "scene_file.hpp"
#include "sim/simulation.hpp"

namespace flagsim {
namespace {

/// The breeze preset at cols x rows nodes, `threads` workers.
void BM_SymplecticEulerStep(benchmark::State& bench) {
  Scene scene = LoadScene("breeze");
  scene.sim.cols = static_cast<int>(bench.range(0));
  scene.sim.rows = static_cast<int>(bench.range(1));
  scene.sim.threads = static_cast<int>(bench.range(2));
  sim::Simulation<float> simulation(scene.sim, scene.wind, scene.seed);
  for (int i = 0; i < 20; ++i) simulation.Step();  // past the first, flat steps
  for (auto _ : bench) simulation.Step();
  const double node_steps = double(simulation.model().num_nodes()) * simulation.substeps();
  bench.counters["substeps"] = simulation.substeps();
  bench.counters["per_node_step"] = benchmark::Counter(
      node_steps * double(bench.iterations()), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_SymplecticEulerStep)
    ->ArgNames({"cols", "rows", "threads"})
    ->Args({32, 24, 1})
    ->Args({64, 48, 1})
    ->Args({128, 96, 1})
    ->Args({256, 192, 1})
    ->Args({32, 24, 2})
    ->Args({64, 48, 2})
    ->Args({128, 96, 2})
    ->Args({256, 192, 2})
    ->UseRealTime()  // wall time: with worker threads, the main thread's CPU time says little
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace flagsim

BENCHMARK_MAIN();
