// What a model of the flag costs, as a model, not a stopwatch: the automatic model chooses by it,
// so that its choice does not depend on how busy the machine is at that moment.
//
//   CPU seconds per step = nodes (substeps w_integrator (iterations) + passes w_collision)
//   CPU seconds per simulated second = that / dt
// w_integrator: seconds per node-substep of one integrator's step with its forces (for XPBD and
// projective dynamics, a + b iterations); w_collision: seconds per node of one self-collision
// pass (its culling, proximity and impulses at the motion a flying flag has). Fitted by
// `lab cost-model` on one thread (the figures in cost_model.cpp say where and when); STATUS
// measures what a step really takes, and the ratio of the two is what the machine's speed and
// load are today.
#pragma once

#include "server/sim/sim_params.hpp"

namespace flagsim::model {

struct IntegratorCost {
  double per_node_substep = 0;            ///< s
  double per_node_substep_iteration = 0;  ///< s, XPBD and projective dynamics only
};

struct CostModel {
  IntegratorCost integrators[8];      ///< in IntegratorKind order
  double per_node_collision_pass = 0;  ///< s

  /// The fitted model (cost_model.cpp).
  static const CostModel& Fitted();

  /// CPU seconds per step of `params`' integrator at `substeps`, with `passes` self-collision
  /// passes (0 without self-collision), on one thread.
  double SecondsPerStep(const sim::SimParams& params, int substeps, double passes) const;
  /// CPU seconds per simulated second: SecondsPerStep / dt.
  double RealTimeFraction(const sim::SimParams& params, int substeps, double passes) const {
    return SecondsPerStep(params, substeps, passes) / params.dt;
  }
};

}  // namespace flagsim::model
