// Where explicit methods fail: the largest stable step, measured, against the theory of the
// grid's highest natural frequency.
#pragma once

#include "sim/sim_params.hpp"
#include "trajectory.hpp"

namespace flagsim::lab {

/// The largest substep at which trial.params.integrator keeps the flag sound (StateIsSound)
/// for trial.horizon from rest, by bisection on [low, high] to a relative width of `precision`:
/// `high` if that is stable, `low` if even that is not.
double LargestStableStep(const Trial& trial, double low, double high, double precision = 0.02);

/// rad/s: the highest natural frequency sqrt(max eig M^-1 K) of the flag at rest, pinned nodes
/// held, from a dense symmetric eigensolve (for small grids: O(n^3) in the free coordinates).
double HighestFrequency(const sim::SimParams& params);

}  // namespace flagsim::lab
