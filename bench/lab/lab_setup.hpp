// What the lab's experiments share: the flags they run, the integrators they compare, the step
// sweeps, and the reference trajectory every error is measured against.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "lab/trajectory.hpp"
#include "server/sim/cloth_state.hpp"
#include "server/sim/integrator.hpp"

namespace flagsim::lab {

/// A preset scene (its flag, wind and seed) as a trial of `horizon` seconds.
Trial PresetTrial(const std::string& preset, double horizon);

/// Every integrator, in IntegratorKind order.
std::vector<sim::IntegratorKind> AllIntegrators();
bool UnconditionallyStable(const Trial& trial);
bool TakesIterations(sim::IntegratorKind kind);  ///< xpbd, projective

/// The steps to sweep for trial's integrator, coarsest first: from 0.9 of its stability limit
/// (explicit) or 1/60 s (unconditionally stable), halving `count` - 1 times.
std::vector<double> StepSweep(const Trial& trial, int count);

/// Substeps of length close to h that fill the trial's horizon exactly.
int SubstepsFor(const Trial& trial, double h);

/// RK4 in double at `substeps` over the trial, remembered: the reference trajectories.
class References {
 public:
  explicit References(const Trial& trial);
  const sim::ClothState<double>& At(int substeps);
  /// A reference whose own error (its distance from the run at half its step) is below
  /// `target` / 1000 m, or as close as rounding allows; printed.
  struct Converged {
    int substeps;
    double self_error;  ///< m
  };
  Converged Converge(double target);

 private:
  Trial trial_;
  std::map<int, sim::ClothState<double>> runs_;
};

}  // namespace flagsim::lab
