// Thread sweep, like the seed's timing study: wall time per step of the breeze preset's flag
// (symplectic Euler and implicit Euler, float, automatic substeps) at 1 to 4 threads, 32 x 24
// to 512 x 384 nodes; the median of five runs of enough steps to fill a fifth of a second.
// Speedup = time(1) / time(n), efficiency = speedup / n. The machine's core count bounds what
// more threads can give; the determinism of the result at any count is tested elsewhere.
#include <algorithm>
#include <chrono>
#include <thread>

#include "experiments.hpp"
#include "lab_setup.hpp"
#include "scene_file.hpp"
#include "sim/simulation.hpp"
#include "table.hpp"

namespace flagsim::lab {
namespace {

double WallSeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// Median wall seconds per step.
double SecondsPerStep(sim::Simulation<float>* simulation) {
  std::vector<double> runs;
  for (int run = 0; run < 5; ++run) {
    int steps = 0;
    const double start = WallSeconds();
    while (WallSeconds() - start < 0.2 || steps == 0) {
      simulation->Step();
      ++steps;
    }
    runs.push_back((WallSeconds() - start) / steps);
  }
  std::nth_element(runs.begin(), runs.begin() + 2, runs.end());
  return runs[2];
}

}  // namespace

void Threads(const std::string& csv) {
  const Scene scene = LoadScene("breeze");
  std::printf("# %u hardware threads\n", std::thread::hardware_concurrency());
  Table table({"integrator", "cols", "rows", "threads", "ms_per_step", "speedup", "efficiency"}, csv);
  // One block of rows per integrator and thread count (the charts join consecutive rows).
  for (const sim::IntegratorKind kind :
       {sim::IntegratorKind::kSymplecticEuler, sim::IntegratorKind::kImplicitEuler}) {
    std::vector<double> one_thread;
    for (const int threads : {1, 2, 3, 4}) {
      for (int scale = 1, grid = 0; scale <= 16; scale *= 2, ++grid) {
        sim::SimParams params = scene.sim;
        params.cols = 32 * scale;
        params.rows = 24 * scale;
        params.integrator = kind;
        params.threads = threads;
        sim::Simulation<float> simulation(params, scene.wind, scene.seed);
        for (int i = 0; i < 3; ++i) simulation.Step();
        const double seconds = SecondsPerStep(&simulation);
        if (threads == 1) one_thread.push_back(seconds);
        const double speedup = one_thread[grid] / seconds;
        table.Add({sim::IntegratorName(kind), std::to_string(params.cols), std::to_string(params.rows),
                   std::to_string(threads), Table::Number(1e3 * seconds), Table::Number(speedup),
                   Table::Number(speedup / threads)});
      }
    }
  }
}

}  // namespace flagsim::lab
