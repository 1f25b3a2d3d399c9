// Work against precision. The breeze preset (32 x 24 nodes, gusts on) for 0.2 s from rest;
// each integrator over seven steps halving from its stability limit or 1/60 s, and xpbd and
// projective at 2, 10 and 50 iterations. Error: against converged RK4, as RMS node distance
// (m) and on the default camera's 1280 x 720 image (px). Cost: CPU seconds per simulated
// second on one thread, in float as the server runs (median of three).
#include <cmath>

#include "experiments.hpp"
#include "lab/screen_error.hpp"
#include "lab_setup.hpp"
#include "scene_file.hpp"
#include "table.hpp"

namespace flagsim::lab {

void WorkPrecision(const std::string& csv) {
  const Trial base = PresetTrial("breeze", 0.2);
  const render::Camera camera = LoadScene("breeze").camera;
  References references(base);
  const sim::ClothState<double>& reference = references.At(references.Converge(1e-8).substeps);
  Table table({"integrator", "iterations", "h_s", "error_m", "error_px", "largest_px", "cost_s_per_s"}, csv);
  for (const sim::IntegratorKind kind : AllIntegrators()) {
    const std::vector<int> iteration_counts =
        TakesIterations(kind) ? std::vector<int>{2, 10, 50} : std::vector<int>{base.params.solver_iterations};
    for (const int iterations : iteration_counts) {
      Trial trial = base;
      trial.params.integrator = kind;
      trial.params.solver_iterations = iterations;
      for (const double h : StepSweep(trial, 7)) {
        const int substeps = SubstepsFor(trial, h);
        const sim::ClothState<double> state = RunFixed<double>(trial, substeps);
        const bool sound = StateIsSound(state);
        const double error = sound ? RmsDistance(state, reference) : INFINITY;
        const ScreenError pixels =
            sound ? ScreenDistance(camera, state, reference) : ScreenError{INFINITY, INFINITY};
        table.Add({sim::IntegratorName(kind), TakesIterations(kind) ? std::to_string(iterations) : "-",
                   Table::Number(trial.horizon / substeps), Table::Number(error), Table::Number(pixels.rms),
                   Table::Number(pixels.largest), Table::Number(CostPerSimulatedSecond(trial, substeps, 3))});
      }
    }
  }
}

}  // namespace flagsim::lab
