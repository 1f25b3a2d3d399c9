// Where explicit methods fail: the largest stable step, measured, against the theory of the
// grid's highest natural frequency.
#pragma once

#include <cmath>

#include "lab/trajectory.hpp"
#include "server/sim/sim_params.hpp"

namespace flagsim::lab {

/// The largest substep at which trial.params.integrator keeps the flag sound (StateIsSound)
/// for trial.horizon from rest, by bisection on [low, high] to a relative width of `precision`:
/// `high` if that is stable, `low` if even that is not.
double LargestStableStep(const Trial& trial, double low, double high, double precision = 0.02);

/// The largest eigenvalue of M^-1 K ((rad/s)^2), or of M^-1 C with `of_damping` (1/s), for the
/// flag at rest with its pinned nodes held, from a dense symmetric eigensolve (for small grids:
/// O(n^3) in the free coordinates).
double TopEigenvalue(const sim::SimParams& params, bool of_damping);

/// rad/s: the highest natural frequency, sqrt of TopEigenvalue of M^-1 K.
inline double HighestFrequency(const sim::SimParams& params) {
  return std::sqrt(TopEigenvalue(params, false));
}

/// The stiffest mode the flag has in one state: the top eigenvalue of M^-1 K(x), K(x) the
/// tangent stiffness there (each spring's exact Hessian in the regime it is in, so a compressed
/// spring is softer, a stretched one stiffer across; plus the bending's B Q), and that mode's
/// damping rate v^T M^-1/2 C M^-1/2 v on its unit eigenvector v (C the springs' c u u^T at x, the
/// bending's beta B Q, and friction).
struct StiffestMode {
  double omega_squared = 0;  ///< (rad/s)^2
  double damping_rate = 0;   ///< 1/s
};
StiffestMode StiffestModeAt(const sim::SimParams& params, const sim::ClothState<double>& state);

}  // namespace flagsim::lab
