// The lab's unit of work: one flag run from rest for a fixed time with one integrator at a
// fixed substep (no automatic substeps, no guard), and what can be said about the result: its
// distance from another run, whether it stayed sound, what it cost.
#pragma once

#include <cstdint>
#include <functional>

#include "server/sim/cloth_state.hpp"
#include "server/sim/sim_params.hpp"
#include "server/sim/wind_field.hpp"

namespace flagsim::lab {

/// A flag, its wind and how long to run it.
struct Trial {
  sim::SimParams params;
  sim::WindSettings wind;
  uint64_t seed = 1;
  double horizon = 0.1;  ///< s of simulated time
};

/// The state after trial.horizon seconds from rest, in `substeps` equal substeps of
/// trial.params.integrator. A run that goes unsound (StateIsSound) stops there. `observe`, if
/// given, sees the state after every substep.
template <typename Real>
sim::ClothState<Real> RunFixed(const Trial& trial, int substeps,
                               const std::function<void(const sim::ClothState<Real>&)>& observe = {});

/// Seconds of this thread's CPU time that `run` takes, the median of `repeats` calls.
double MedianCpuSeconds(int repeats, const std::function<void()>& run);

/// Seconds of this thread's CPU time to do RunFixed<float> (what the server pays), the median of
/// `repeats` runs, over trial.horizon: the cost per simulated second.
double CostPerSimulatedSecond(const Trial& trial, int substeps, int repeats);

/// m: root mean square over nodes of the distance between the nodes of a and b.
double RmsDistance(const sim::ClothState<double>& a, const sim::ClothState<double>& b);

/// Any node faster than this (m/s) is taken for a blow-up.
constexpr double kRunawaySpeed = 100.0;

/// True if every coordinate and velocity is finite and no node is faster than kRunawaySpeed.
template <typename Real>
bool StateIsSound(const sim::ClothState<Real>& state);

}  // namespace flagsim::lab
