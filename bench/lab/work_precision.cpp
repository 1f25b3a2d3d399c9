// Work against precision. The breeze preset (32 x 24 nodes, gusts on) for 0.2 s from rest;
// each integrator over seven steps halving from its stability limit or 1/60 s, and xpbd and
// projective at 2, 10 and 50 iterations. Error: against converged RK4, as RMS node distance
// (m) and on the default camera's 1280 x 720 image (px). Cost: CPU seconds per simulated
// second on one thread, in float as the server runs (median of three). bullet_bench
// --work-precision adds Bullet's soft body to the same table (work_precision_scene.hpp).
#include "bench/lab/experiments.hpp"
#include "bench/lab/lab_setup.hpp"
#include "bench/lab/table.hpp"
#include "bench/lab/work_precision_scene.hpp"

namespace flagsim::lab {

void WorkPrecision(const std::string& csv) {
  const WorkPrecisionScene scene = LoadWorkPrecisionScene();
  Table table(WorkPrecisionColumns(), csv);
  for (const sim::IntegratorKind kind : AllIntegrators()) {
    const std::vector<int> iteration_counts = TakesIterations(kind)
                                                  ? std::vector<int>{2, 10, 50}
                                                  : std::vector<int>{scene.trial.params.solver_iterations};
    for (const int iterations : iteration_counts) {
      Trial trial = scene.trial;
      trial.params.integrator = kind;
      trial.params.solver_iterations = iterations;
      for (const double h : StepSweep(trial, 7)) {
        const int substeps = SubstepsFor(trial, h);
        table.Add(WorkPrecisionRow(scene, sim::IntegratorName(kind),
                                   TakesIterations(kind) ? std::to_string(iterations) : "-",
                                   trial.horizon / substeps, RunFixed<double>(trial, substeps),
                                   CostPerSimulatedSecond(trial, substeps, 3)));
      }
    }
  }
}

}  // namespace flagsim::lab
