// Where explicit methods fail: the largest stable step, measured, against the theory of the
// grid's highest natural frequency.
#pragma once

#include <cmath>

#include "server/lab/trajectory.hpp"
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

}  // namespace flagsim::lab
