// The stability map. A 16 x 12 breeze flag in steady wind for 1 s from rest, at structural
// stiffness from 100 to 100,000 N/m (shear and bending stiffness scaled with it); for each
// integrator the largest step that keeps it sound (finite, no node faster than 100 m/s),
// by bisection, beside two theories and a claim:
//   rest     the limit on the highest frequency of the flag at rest, w_max (dense eigensolve,
//            every spring at its stretched stiffness);
//   states   the same limit on the frequencies the flag really has: the stiffest mode of the
//            tangent stiffness (compressed springs softer, stretched ones stiffer across) at the
//            states the run at the measured step passes through, every 50 ms, the highest of
//            them; for explicit Euler that mode's own damping;
//   claimed  what the integrator's StableStep claims from the server's bound, of which the
//            server uses 0.8.
// The limits: 2 / w for symplectic Euler, the seed's scheme and Verlet; 2 sqrt(2) / w for RK4
// (its stability region meets the imaginary axis there: an undamped oscillation's eigenvalues
// +-i w lie on it; 2.785 / w holds on the real axis only); for explicit Euler the damping bound
// c / w^2 (x'' + c x' + w^2 x = 0 is stable under forward Euler for h < c / w^2; undamped, never).
// Unconditionally stable integrators are tried up to 0.1 s.
#include <cmath>

#include "bench/lab/experiments.hpp"
#include "bench/lab/lab_setup.hpp"
#include "bench/lab/table.hpp"
#include "lab/stability.hpp"
#include "server/sim/cloth_model.hpp"
#include "server/sim/forces.hpp"

namespace flagsim::lab {
namespace {

constexpr double kLargestTried = 0.1;  ///< s

/// The trial with structural stiffness `stiffness`, shear and bending stiffness scaled alike.
Trial Stiffened(Trial trial, double stiffness) {
  const double scale = stiffness / trial.params.forces.stiffness;
  trial.params.forces.stiffness = stiffness;
  trial.params.forces.shear_stiffness *= scale;
  trial.params.forces.bending_stiffness *= scale;
  return trial;
}

/// The step limit of `kind` on a mode of angular frequency w (rad/s) damped at rate c (1/s), in
/// `params` (the seed's scheme scales every force by 1 - friction, so its modes are slower by
/// sqrt(1 - friction)).
double Limit(const sim::SimParams& params, double w, double c) {
  switch (params.integrator) {
    case sim::IntegratorKind::kSymplecticEuler:
    case sim::IntegratorKind::kVelocityVerlet:
      return 2 / w;
    case sim::IntegratorKind::kSeed:
      return 2 / (w * std::sqrt(1 - params.forces.friction));
    case sim::IntegratorKind::kRk4:
      return 2 * std::sqrt(2.0) / w;
    case sim::IntegratorKind::kExplicitEuler:
      return c / (w * w);
    default:
      return INFINITY;
  }
}

/// The limit on the stiffest mode of the states a run of `trial` at substep h passes through,
/// every 50 ms: the smallest of the limits there.
double LimitOnTheStates(const Trial& trial, double h) {
  const int substeps = static_cast<int>(std::ceil(trial.horizon / h));
  Trial exact = trial;
  exact.horizon = substeps * h;
  const int every = std::max(1, int(std::lround(0.05 / h)));
  double limit = INFINITY;
  int count = 0;
  RunFixed<double>(exact, substeps, [&](const sim::ClothState<double>& state) {
    if (++count % every != 0) return;
    const StiffestMode mode = StiffestModeAt(trial.params, state);
    limit = std::min(limit, Limit(trial.params, std::sqrt(mode.omega_squared), mode.damping_rate));
  });
  return limit;
}

}  // namespace

void StabilityMap(const std::string& csv) {
  Trial base = PresetTrial("breeze", 1.0);
  base.params.cols = 16;
  base.params.rows = 12;
  base.wind.gust = 0;
  Table table({"integrator", "stiffness_N_per_m", "w_max_rad_per_s", "largest_stable_h_s", "theory_h_s",
               "states_theory_h_s", "measured_over_states", "claimed_h_s"},
              csv);
  // One block of rows per integrator (the charts join a series' consecutive rows).
  const std::vector<double> stiffnesses = {100.0, 300.0, 1e3, 3e3, 1e4, 3e4, 1e5};
  std::vector<double> w_max;
  for (const double stiffness : stiffnesses)
    w_max.push_back(HighestFrequency(Stiffened(base, stiffness).params));
  for (const sim::IntegratorKind kind : AllIntegrators()) {
    for (size_t i = 0; i < stiffnesses.size(); ++i) {
      Trial trial = Stiffened(base, stiffnesses[i]);
      trial.params.integrator = kind;
      const sim::ClothModel<double> model = sim::BuildClothModel<double>(trial.params);
      const sim::FrequencyBound bound = sim::EstimateFrequencyBound(model, sim::AirFriction(trial.params));
      const double claimed = sim::MakeIntegrator<double>(kind)->StableStep(bound);
      const double low = std::isfinite(claimed) ? claimed / 8 : 1e-4;
      const double high = std::isfinite(claimed) ? std::min(8 * claimed, kLargestTried) : kLargestTried;
      const double measured = LargestStableStep(trial, low, high);
      const double rest_damping = bound.stiffness_damping_ratio * w_max[i] * w_max[i] + bound.friction;
      const double on_states = std::isfinite(claimed) ? LimitOnTheStates(trial, measured) : INFINITY;
      table.Add({sim::IntegratorName(kind), Table::Number(stiffnesses[i]), Table::Number(w_max[i]),
                 Table::Number(measured), Table::Number(Limit(trial.params, w_max[i], rest_damping)),
                 Table::Number(on_states), Table::Number(measured / on_states), Table::Number(claimed)});
    }
  }
}

}  // namespace flagsim::lab
