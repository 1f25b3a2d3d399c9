#include "trajectory.hpp"

#include <algorithm>
#include <cmath>

#include "sim/cloth_model.hpp"
#include "sim/forces.hpp"
#include "sim/integrator.hpp"

namespace flagsim::lab {

sim::ClothState<double> RunFixed(const Trial& trial, int substeps) {
  const sim::ClothModel<double> model = sim::BuildClothModel<double>(trial.params);
  const sim::WindField wind(trial.wind, trial.seed);
  sim::ForceEvaluator<double> evaluator;
  const auto integrator = sim::MakeIntegrator<double>(trial.params.integrator);
  const sim::StepContext<double> context{model, trial.params, wind, evaluator};
  sim::ClothState<double> state = sim::RestState(model);
  const double h = trial.horizon / substeps;
  for (int i = 0; i < substeps; ++i) {
    integrator->Substep(context, h, &state);
    state.time = (i + 1) * h;  // no drift of the clock from repeated sums
  }
  return state;
}

double RmsDistance(const sim::ClothState<double>& a, const sim::ClothState<double>& b) {
  double sum = 0;
  const int n = a.num_nodes();
  for (int i = 0; i < n; ++i) {
    const double dx = a.x[i] - b.x[i], dy = a.y[i] - b.y[i], dz = a.z[i] - b.z[i];
    sum += dx * dx + dy * dy + dz * dz;
  }
  return n > 0 ? std::sqrt(sum / n) : 0.0;
}

bool StateIsSound(const sim::ClothState<double>& state, double runaway) {
  for (int i = 0; i < state.num_nodes(); ++i) {
    const double values[6] = {state.x[i], state.y[i], state.z[i], state.vx[i], state.vy[i], state.vz[i]};
    if (!std::all_of(values, values + 6, [](double v) { return std::isfinite(v); })) return false;
    if (std::max({std::abs(values[3]), std::abs(values[4]), std::abs(values[5])}) > runaway) return false;
  }
  return true;
}

}  // namespace flagsim::lab
