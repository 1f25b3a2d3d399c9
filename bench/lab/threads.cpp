// Thread sweep, like the seed's timing study: wall time per step of the breeze preset's flag
// (symplectic Euler and implicit Euler, float, automatic substeps) at 1 to 4 threads, 32 x 24
// to 512 x 384 nodes. The thread counts take turns, five rounds of a fifth of a second each (or
// one step, if longer), so that a change in the machine's speed meets all of them alike:
// ms per step is the median of its rounds, speedup the median over rounds of time(1) / time(n)
// in the same round, efficiency = speedup / n. The machine's core count bounds what more threads
// can give; the determinism of the result at any count is tested elsewhere.
#include <algorithm>
#include <chrono>
#include <memory>
#include <thread>

#include "bench/lab/experiments.hpp"
#include "bench/lab/lab_setup.hpp"
#include "bench/lab/table.hpp"
#include "server/scene/scene_file.hpp"
#include "server/sim/simulation.hpp"

namespace flagsim::lab {
namespace {

double WallSeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// Wall seconds per step over a fifth of a second of steps (at least one).
double SecondsPerStep(sim::Simulation<float>* simulation) {
  int steps = 0;
  const double start = WallSeconds();
  while (WallSeconds() - start < 0.2 || steps == 0) {
    simulation->Step();
    ++steps;
  }
  return (WallSeconds() - start) / steps;
}

double Median(std::vector<double> values) {
  const auto middle = values.begin() + values.size() / 2;
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

constexpr int kRounds = 5;
constexpr int kMaxThreads = 4;

/// One grid and integrator at 1 to kMaxThreads threads, in turns: seconds[threads - 1][round].
std::vector<std::vector<double>> TimeInTurns(const sim::SimParams& base, const Scene& scene) {
  std::vector<std::unique_ptr<sim::Simulation<float>>> simulations;
  for (int threads = 1; threads <= kMaxThreads; ++threads) {
    sim::SimParams params = base;
    params.threads = threads;
    simulations.push_back(std::make_unique<sim::Simulation<float>>(params, scene.wind, scene.seed));
    for (int i = 0; i < 3; ++i) simulations.back()->Step();
  }
  std::vector<std::vector<double>> seconds(kMaxThreads);
  for (int round = 0; round < kRounds; ++round) {
    for (int t = 0; t < kMaxThreads; ++t) seconds[t].push_back(SecondsPerStep(simulations[t].get()));
  }
  return seconds;
}

}  // namespace

void Threads(const std::string& csv) {
  const Scene scene = LoadScene("breeze");
  std::printf("# %u hardware threads\n", std::thread::hardware_concurrency());
  Table table({"integrator", "cols", "rows", "threads", "ms_per_step", "speedup", "efficiency"}, csv);
  // One block of rows per integrator and thread count (the charts join consecutive rows).
  for (const sim::IntegratorKind kind :
       {sim::IntegratorKind::kSymplecticEuler, sim::IntegratorKind::kImplicitEuler}) {
    std::vector<sim::SimParams> grids;
    std::vector<std::vector<std::vector<double>>> timings;  // [grid][threads - 1][round]
    for (int scale = 1; scale <= 16; scale *= 2) {
      sim::SimParams params = scene.sim;
      params.cols = 32 * scale;
      params.rows = 24 * scale;
      params.integrator = kind;
      grids.push_back(params);
      timings.push_back(TimeInTurns(params, scene));
    }
    for (int threads = 1; threads <= kMaxThreads; ++threads) {
      for (size_t grid = 0; grid < grids.size(); ++grid) {
        const std::vector<std::vector<double>>& seconds = timings[grid];
        std::vector<double> speedups;
        for (int round = 0; round < kRounds; ++round)
          speedups.push_back(seconds[0][round] / seconds[threads - 1][round]);
        const double speedup = Median(speedups);
        table.Add({sim::IntegratorName(kind), std::to_string(grids[grid].cols),
                   std::to_string(grids[grid].rows), std::to_string(threads),
                   Table::Number(1e3 * Median(seconds[threads - 1])), Table::Number(speedup),
                   Table::Number(speedup / threads)});
      }
    }
  }
}

}  // namespace flagsim::lab
