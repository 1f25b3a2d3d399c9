#include "bench/lab/lab_setup.hpp"

#include <cmath>
#include <cstdio>

#include "server/scene/scene_file.hpp"
#include "server/sim/cloth_model.hpp"
#include "server/sim/forces.hpp"

namespace flagsim::lab {

Trial PresetTrial(const std::string& preset, double horizon) {
  const Scene scene = LoadScene(preset);
  Trial trial;
  trial.params = scene.sim;
  trial.params.threads = 1;
  trial.wind = scene.wind;
  trial.seed = scene.seed;
  trial.horizon = horizon;
  return trial;
}

std::vector<sim::IntegratorKind> AllIntegrators() {
  std::vector<sim::IntegratorKind> kinds;
  for (size_t i = 0; i < sim::IntegratorNames().size(); ++i) kinds.push_back(sim::IntegratorKind(i));
  return kinds;
}

bool UnconditionallyStable(const Trial& trial) {
  const sim::ClothModel<double> model = sim::BuildClothModel<double>(trial.params);
  const auto bound = sim::EstimateFrequencyBound(model, sim::AirFriction(trial.params));
  return !std::isfinite(sim::MakeIntegrator<double>(trial.params.integrator)->StableStep(bound));
}

bool TakesIterations(sim::IntegratorKind kind) {
  return kind == sim::IntegratorKind::kXpbd || kind == sim::IntegratorKind::kProjectiveDynamics;
}

std::vector<double> StepSweep(const Trial& trial, int count) {
  double h = 1.0 / 60;
  if (!UnconditionallyStable(trial)) {
    const sim::ClothModel<double> model = sim::BuildClothModel<double>(trial.params);
    const auto bound = sim::EstimateFrequencyBound(model, sim::AirFriction(trial.params));
    h = 0.9 * sim::MakeIntegrator<double>(trial.params.integrator)->StableStep(bound);
  }
  std::vector<double> steps;
  for (int i = 0; i < count; ++i, h /= 2) steps.push_back(h);
  return steps;
}

int SubstepsFor(const Trial& trial, double h) { return std::max(1, int(std::lround(trial.horizon / h))); }

References::References(const Trial& trial) : trial_(trial) {
  trial_.params.integrator = sim::IntegratorKind::kRk4;
}

const sim::ClothState<double>& References::At(int substeps) {
  auto found = runs_.find(substeps);
  if (found == runs_.end()) found = runs_.emplace(substeps, RunFixed<double>(trial_, substeps)).first;
  return found->second;
}

References::Converged References::Converge(double target) {
  int substeps = SubstepsFor(trial_, 0.5 * StepSweep(trial_, 1)[0]);
  double self_error = RmsDistance(At(substeps), At(2 * substeps));
  while (self_error > 1e-3 * target && substeps < (1 << 22)) {
    substeps *= 2;
    self_error = RmsDistance(At(substeps), At(2 * substeps));
  }
  std::printf(
      "# reference: RK4 in double, %d substeps over %g s (h = %.3g s); it and the run at half its step "
      "differ by %.3g m RMS\n",
      2 * substeps, trial_.horizon, trial_.horizon / (2 * substeps), self_error);
  return {2 * substeps, self_error};
}

}  // namespace flagsim::lab
