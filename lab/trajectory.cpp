#include "lab/trajectory.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "lab/cpu_time.hpp"
#include "server/sim/cloth_model.hpp"
#include "server/sim/forces.hpp"
#include "server/sim/integrator.hpp"

namespace flagsim::lab {
namespace {

constexpr int kSoundnessInterval = 64;  ///< substeps between checks for a blow-up

}  // namespace

template <typename Real>
sim::ClothState<Real> RunFixed(const Trial& trial, int substeps,
                               const std::function<void(const sim::ClothState<Real>&)>& observe) {
  const sim::ClothModel<Real> model = sim::BuildClothModel<Real>(trial.params);
  const sim::WindField wind(trial.wind, trial.seed);
  sim::ForceEvaluator<Real> evaluator;
  const auto integrator = sim::MakeIntegrator<Real>(trial.params.integrator);
  const sim::StepContext<Real> context{model, trial.params, wind, evaluator};
  sim::ClothState<Real> state = sim::RestState(model);
  const double h = trial.horizon / substeps;
  for (int i = 0; i < substeps; ++i) {
    integrator->Substep(context, h, &state);
    state.time = (i + 1) * h;  // no drift of the clock from repeated sums
    if (observe) observe(state);
    if (i % kSoundnessInterval == 0 && !StateIsSound(state)) break;
  }
  return state;
}

double MedianCpuSeconds(int repeats, const std::function<void()>& run) {
  std::vector<double> seconds;
  for (int i = 0; i < repeats; ++i) {
    const double start = ThreadCpuSeconds();
    run();
    seconds.push_back(ThreadCpuSeconds() - start);
  }
  std::nth_element(seconds.begin(), seconds.begin() + seconds.size() / 2, seconds.end());
  return seconds[seconds.size() / 2];
}

double CostPerSimulatedSecond(const Trial& trial, int substeps, int repeats) {
  return MedianCpuSeconds(repeats, [&] { RunFixed<float>(trial, substeps); }) / trial.horizon;
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

template <typename Real>
bool StateIsSound(const sim::ClothState<Real>& state) {
  for (int i = 0; i < state.num_nodes(); ++i) {
    const double values[6] = {state.x[i], state.y[i], state.z[i], state.vx[i], state.vy[i], state.vz[i]};
    if (!std::all_of(values, values + 6, [](double v) { return std::isfinite(v); })) return false;
    const double speed_squared = values[3] * values[3] + values[4] * values[4] + values[5] * values[5];
    if (speed_squared > kRunawaySpeed * kRunawaySpeed) return false;
  }
  return true;
}

template sim::ClothState<float> RunFixed<float>(const Trial&, int,
                                                const std::function<void(const sim::ClothState<float>&)>&);
template sim::ClothState<double> RunFixed<double>(const Trial&, int,
                                                  const std::function<void(const sim::ClothState<double>&)>&);
template bool StateIsSound<float>(const sim::ClothState<float>&);
template bool StateIsSound<double>(const sim::ClothState<double>&);

}  // namespace flagsim::lab
