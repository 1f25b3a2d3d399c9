// The stability map. A 16 x 12 breeze flag in steady wind for 1 s from rest, at structural
// stiffness from 100 to 100,000 N/m (shear and bend moduli scaled with it); for each
// integrator the largest step that keeps it sound (finite, no node faster than 100 m/s),
// by bisection, beside:
//   theory   the limit on the grid's exact highest frequency w_max (dense eigensolve): 2 / w_max
//            for symplectic Euler, the seed's scheme and Verlet, 2.61 / w_max for RK4 (its half
//            disc; 2.83 on the imaginary axis), and for explicit Euler the damping bound
//            ratio + friction / w_max^2, since without damping no step is stable;
//   claimed  what the integrator's StableStep claims from the Gershgorin bound, of which the
//            server uses 0.8.
// Unconditionally stable integrators are tried up to 0.1 s.
#include <cmath>

#include "bench/lab/experiments.hpp"
#include "bench/lab/lab_setup.hpp"
#include "bench/lab/table.hpp"
#include "server/lab/stability.hpp"
#include "server/sim/cloth_model.hpp"
#include "server/sim/forces.hpp"

namespace flagsim::lab {
namespace {

constexpr double kLargestTried = 0.1;  ///< s

double Theory(sim::IntegratorKind kind, double w_max, const sim::FrequencyBound& bound) {
  switch (kind) {
    case sim::IntegratorKind::kSymplecticEuler:
    case sim::IntegratorKind::kSeed:
    case sim::IntegratorKind::kVelocityVerlet:
      return 2 / w_max;
    case sim::IntegratorKind::kRk4:
      return 2.61 / w_max;
    case sim::IntegratorKind::kExplicitEuler:
      return bound.stiffness_damping_ratio + bound.friction / (w_max * w_max);
    default:
      return INFINITY;
  }
}

/// The trial with structural stiffness `stiffness`, shear and bend moduli scaled alike.
Trial Stiffened(Trial trial, double stiffness) {
  const double scale = stiffness / trial.params.forces.stiffness;
  trial.params.forces.stiffness = stiffness;
  trial.params.forces.shear_stiffness *= scale;
  trial.params.forces.bend_stiffness *= scale;
  return trial;
}

}  // namespace

void StabilityMap(const std::string& csv) {
  Trial base = PresetTrial("breeze", 1.0);
  base.params.cols = 16;
  base.params.rows = 12;
  base.wind.gust = 0;
  Table table({"integrator", "stiffness_N_per_m", "w_max_rad_per_s", "largest_stable_h_s", "theory_h_s",
               "claimed_h_s"},
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
      table.Add({sim::IntegratorName(kind), Table::Number(stiffnesses[i]), Table::Number(w_max[i]),
                 Table::Number(LargestStableStep(trial, low, high)),
                 Table::Number(Theory(kind, w_max[i], bound)), Table::Number(claimed)});
    }
  }
}

}  // namespace flagsim::lab
