// The lab's unit of work: one flag run from rest for a fixed time with one integrator at a
// fixed substep (no automatic substeps, no guard), and the distance between two such runs.
// Everything in double precision, so that what is measured is the method, not the rounding.
#pragma once

#include <cstdint>

#include "sim/cloth_state.hpp"
#include "sim/sim_params.hpp"
#include "sim/wind_field.hpp"

namespace flagsim::lab {

/// A flag, its wind and how long to run it.
struct Trial {
  sim::SimParams params;
  sim::WindSettings wind;
  uint64_t seed = 1;
  double horizon = 0.1;  ///< s of simulated time
};

/// The state after trial.horizon seconds from rest, in `substeps` equal substeps of
/// trial.params.integrator.
sim::ClothState<double> RunFixed(const Trial& trial, int substeps);

/// m: root mean square over nodes of the distance between the nodes of a and b.
double RmsDistance(const sim::ClothState<double>& a, const sim::ClothState<double>& b);

/// True if every coordinate and velocity is finite and no node is faster than `runaway` m/s.
bool StateIsSound(const sim::ClothState<double>& state, double runaway);

}  // namespace flagsim::lab
