// The cost model's fit (server/model/cost_model.hpp). Each integrator on the breeze at 64 x 48 and
// 128 x 96, without self-collision, flown 1 s from rest, then timed for a quarter second of steps
// in CPU seconds of the stepping thread: seconds per node-substep (for XPBD and projective
// dynamics at 2 and 10 iterations, fitted as a + b iterations). Then XPBD at 2 iterations with
// and without self-collision from the same snapshot at 32 x 24, 64 x 48 and 128 x 96: the
// difference per node and pass, fitted as w_ref (nodes / 3072)^g. Prints the figures and the
// constants for cost_model.cpp.
#include <algorithm>
#include <cmath>
#include <iterator>
#include <cstdio>

#include "bench/lab/experiments.hpp"
#include "bench/lab/lab_setup.hpp"
#include "bench/lab/table.hpp"
#include "lab/cpu_time.hpp"
#include "server/scene/scene_file.hpp"
#include "server/sim/simulation.hpp"

namespace flagsim::lab {
namespace {

constexpr double kMeasureSeconds = 0.25;
constexpr double kCollisionReferenceNodes = 3072;  ///< 64 x 48

struct Timing {
  double per_step = 0;  ///< s of CPU
  double substeps = 0;  ///< per step, the mean
  double passes = 0;    ///< self-collision passes per step, the mean
};

/// Times steps of a simulation resumed from `snapshot` for at least kMeasureSeconds of CPU.
Timing Time(const sim::SimulationSnapshot<float>& snapshot) {
  sim::Simulation<float> simulation(snapshot);
  Timing timing;
  int steps = 0;
  timing.per_step = CpuSecondsPerCall(
      kMeasureSeconds,
      [&] {
        simulation.Step();
        timing.substeps += simulation.substeps();
        timing.passes += simulation.self_collision_stats().passes;
      },
      &steps);
  timing.substeps /= steps;
  timing.passes /= steps;
  return timing;
}

sim::SimulationSnapshot<float> Flown(sim::SimParams params, const Scene& scene) {
  params.threads = 1;
  sim::Simulation<float> simulation(params, scene.wind, scene.seed);
  for (int i = 0; i < int(1.0 / params.dt); ++i) simulation.Step();
  return simulation.Snapshot();
}

}  // namespace

void CostModelFit(const std::string& csv) {
  const Scene scene = LoadScene("breeze");
  Table table({"what", "grid", "iterations", "substeps", "passes", "ms_per_step", "ns_per_node_unit"}, csv);
  std::string constants;
  for (const sim::IntegratorKind kind : AllIntegrators()) {
    double sum = 0, iteration_slope = 0;
    int count = 0;
    for (const int scale : {2, 4}) {
      sim::SimParams params = scene.sim;
      params.cols = 32 * scale;
      params.rows = 24 * scale;
      params.integrator = kind;
      params.self_collision = false;
      const double nodes = double(params.cols) * params.rows;
      const bool iterates = TakesIterations(kind);
      double per_iteration[2] = {0, 0};
      for (const int iterations : iterates ? std::vector<int>{2, 10} : std::vector<int>{params.solver_iterations}) {
        params.solver_iterations = iterations;
        const Timing timing = Time(Flown(params, scene));
        const double unit = timing.per_step / (nodes * timing.substeps);
        table.Add({sim::IntegratorName(kind), std::to_string(params.cols) + "x" + std::to_string(params.rows),
                   std::to_string(iterations), Table::Number(timing.substeps), "0",
                   Table::Number(1e3 * timing.per_step), Table::Number(1e9 * unit)});
        if (iterates) per_iteration[iterations == 2 ? 0 : 1] = unit;
        else sum += unit;
      }
      if (iterates) {  // a + b iterations through the two points, a kept >= 0
        const double slope = (per_iteration[1] - per_iteration[0]) / 8;
        const double intercept = std::max(0.0, per_iteration[0] - 2 * slope);
        iteration_slope += intercept > 0 ? slope : per_iteration[1] / 10;
        sum += intercept;
      }
      ++count;
    }
    char line[160];
    std::snprintf(line, sizeof(line), "    {%.3g, %.3g},  // %s\n", sum / count, iteration_slope / count,
                  sim::IntegratorName(kind).c_str());
    constants += line;
  }
  // Self-collision on XPBD at 2 iterations, the method auto runs on fine grids, at three grids;
  // per node and pass = w_ref (nodes / 3072)^g by least squares in log-log.
  double sum_x = 0, sum_y = 0, sum_xx = 0, sum_xy = 0;
  const int scales[] = {1, 2, 4};
  for (const int scale : scales) {
    sim::SimParams params = scene.sim;
    params.cols = 32 * scale;
    params.rows = 24 * scale;
    params.integrator = sim::IntegratorKind::kXpbd;
    params.solver_iterations = 2;
    const sim::SimulationSnapshot<float> with = Flown(params, scene);
    sim::SimulationSnapshot<float> without = with;
    without.params.self_collision = false;
    const Timing on = Time(with), off = Time(without);
    const double nodes = double(params.cols) * params.rows;
    const double unit = std::max(1e-12, (on.per_step - off.per_step) / (nodes * std::max(1.0, on.passes)));
    table.Add({"collision (xpbd)", std::to_string(params.cols) + "x" + std::to_string(params.rows), "2",
               Table::Number(on.substeps), Table::Number(on.passes), Table::Number(1e3 * (on.per_step - off.per_step)),
               Table::Number(1e9 * unit)});
    const double x = std::log(nodes / kCollisionReferenceNodes), y = std::log(unit);
    sum_x += x, sum_y += y, sum_xx += x * x, sum_xy += x * y;
  }
  const double n = std::size(scales);
  const double growth = (n * sum_xy - sum_x * sum_y) / (n * sum_xx - sum_x * sum_x);
  const double at_reference = std::exp((sum_y - growth * sum_x) / n);
  std::printf("# cost_model.cpp, seconds:\n%s    self-collision: {%.3g, %.0f, %.3g}\n", constants.c_str(), at_reference,
              kCollisionReferenceNodes, growth);
}

}  // namespace flagsim::lab
