#include "server/model/cost_model.hpp"

#include <cmath>

namespace flagsim::model {

// `build/bench/lab cost-model` on 2 vCPUs of an AMD EPYC (Zen 3), g++ 12.2, Release, 2026-11-27:
// the mean of 64 x 48 and 128 x 96 (docs/lab/cost-model.txt). Implicit Euler's and projective
// dynamics' costs per node grow with the grid (more conjugate gradient iterations; a sparse
// factorisation's fill): 2.7 and 6.1 us per node-substep at the two grids for implicit Euler.
const CostModel& CostModel::Fitted() {
  static const CostModel fitted{
      {
          {1.03e-08, 0},         // symplectic_euler
          {9.83e-09, 0},         // seed
          {9.72e-09, 0},         // explicit_euler
          {1.05e-08, 0},         // verlet
          {4.75e-08, 0},         // rk4
          {7.9e-09, 7.86e-08},   // xpbd: a + b iterations
          {4.42e-06, 0},         // implicit_euler
          {5.23e-08, 3.04e-07},  // projective: a + b iterations
      },
      // Self-collision on XPBD at 2 iterations, flown 1 s: 38, 53 and 617 ns per node and pass at
      // 32 x 24, 64 x 48 and 128 x 96 (the finer flag lay on itself over more of its area),
      // fitted as 107 ns at 64 x 48 times (nodes / 3072)^1.01.
      {1.07e-07, 3072, 1.01}};
  return fitted;
}

double CollisionCost::PerNodePass(double nodes) const {
  return per_node_pass * std::pow(nodes / reference_nodes, growth);
}

double CostModel::SecondsPerStep(const sim::SimParams& params, int substeps, double passes) const {
  const IntegratorCost& cost = integrators[static_cast<int>(params.integrator)];
  const double nodes = double(params.cols) * params.rows;
  const bool iterates = params.integrator == sim::IntegratorKind::kXpbd ||
                        params.integrator == sim::IntegratorKind::kProjectiveDynamics;
  const double per_substep =
      cost.per_node_substep + (iterates ? params.solver_iterations * cost.per_node_substep_iteration : 0.0);
  return nodes * (substeps * per_substep + passes * collision.PerNodePass(nodes));
}

}  // namespace flagsim::model
