// What a model of the flag costs, as a model, not a stopwatch: the automatic model chooses by it,
// so that its choice does not depend on how busy the machine is at that moment.
//
//   CPU seconds per step = nodes (substeps w_integrator (iterations) + passes w_collision(nodes))
//   w_collision(nodes)   = w_ref (nodes / nodes_ref)^g
//   CPU seconds per simulated second = that / dt
// w_integrator: seconds per node-substep of one integrator's step with its forces (for XPBD and
// projective dynamics, a + b iterations); w_collision: seconds per node of one self-collision
// pass (its culling, proximity and impulses at the motion a flying flag has). A pass costs more
// per node on a finer grid: a fold of the same size spans more cells, so more pairs of patches
// lie within reach of each other; g is fitted over three grids. Fitted by
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

/// One self-collision pass: seconds per node, growing with the grid as a power of the nodes.
struct CollisionCost {
  double per_node_pass = 0;    ///< s per node and pass at reference_nodes
  double reference_nodes = 1;  ///< where per_node_pass was measured
  double growth = 0;           ///< g: per-node cost ~ nodes^g

  /// Seconds per node and pass on a flag of `nodes` nodes.
  double PerNodePass(double nodes) const;
};

struct CostModel {
  IntegratorCost integrators[8];  ///< in IntegratorKind order
  CollisionCost collision;

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
