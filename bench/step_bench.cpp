// One physics step of the flag at several grid sizes, reported as nanoseconds per node-step
// (one substep of one node: the unit the integrators are compared in).
//
//   build/bench/step_bench [--benchmark_filter=...]
#include <benchmark/benchmark.h>

#include "server/scene/scene_file.hpp"
#include "server/sim/simulation.hpp"

namespace flagsim {
namespace {

/// The breeze preset at cols x rows nodes, `threads` workers, stepped by `integrator`.
void StepBench(benchmark::State& bench, sim::IntegratorKind integrator) {
  Scene scene = LoadScene("breeze");
  scene.sim.cols = static_cast<int>(bench.range(0));
  scene.sim.rows = static_cast<int>(bench.range(1));
  scene.sim.threads = static_cast<int>(bench.range(2));
  scene.sim.integrator = integrator;
  sim::Simulation<float> simulation(scene.sim, scene.wind, scene.seed);
  for (int i = 0; i < 20; ++i) simulation.Step();  // past the first, flat steps
  for (auto _ : bench) simulation.Step();
  const double node_steps = double(simulation.model().num_nodes()) * simulation.substeps();
  bench.counters["substeps"] = simulation.substeps();
  bench.counters["per_node_step"] = benchmark::Counter(
      node_steps * double(bench.iterations()), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_SymplecticEulerStep(benchmark::State& bench) {
  StepBench(bench, sim::IntegratorKind::kSymplecticEuler);
}
void BM_ImplicitEulerStep(benchmark::State& bench) { StepBench(bench, sim::IntegratorKind::kImplicitEuler); }
void BM_ProjectiveDynamicsStep(benchmark::State& bench) {
  StepBench(bench, sim::IntegratorKind::kProjectiveDynamics);
}

/// 32 x 24 to 256 x 192 nodes on one and two threads; wall time (with worker threads, the main
/// thread's CPU time says little).
void GridsAndThreads(benchmark::internal::Benchmark* bench) {
  bench->ArgNames({"cols", "rows", "threads"});
  for (int threads : {1, 2}) {
    for (int scale : {1, 2, 4, 8}) bench->Args({32 * scale, 24 * scale, threads});
  }
  bench->UseRealTime()->Unit(benchmark::kMicrosecond);
}
BENCHMARK(BM_SymplecticEulerStep)->Apply(GridsAndThreads);
BENCHMARK(BM_ImplicitEulerStep)->Apply(GridsAndThreads);
BENCHMARK(BM_ProjectiveDynamicsStep)->Apply(GridsAndThreads);

}  // namespace
}  // namespace flagsim

BENCHMARK_MAIN();
