#include "server/model/cost_model.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace flagsim::model {
namespace {

// The model's arithmetic (its constants are measurements, docs/lab/cost-model.txt): nodes and
// substeps scale the integrator's part, iterations add to XPBD's, passes add the collisions'.
TEST(CostModel, ScalesWithNodesSubstepsIterationsAndPasses) {
  const CostModel& model = CostModel::Fitted();
  sim::SimParams params;
  params.cols = 32;
  params.rows = 24;
  const double base = model.SecondsPerStep(params, 12, 0);
  EXPECT_DOUBLE_EQ(base, 768 * 12 * model.integrators[0].per_node_substep);
  params.cols = 64;
  EXPECT_DOUBLE_EQ(model.SecondsPerStep(params, 12, 0), 2 * base);
  EXPECT_DOUBLE_EQ(model.SecondsPerStep(params, 24, 0), 4 * base);
  EXPECT_NEAR(model.SecondsPerStep(params, 24, 2) - model.SecondsPerStep(params, 24, 0),
              2 * 64 * 24 * model.collision.PerNodePass(64 * 24), 1e-15);
  params.integrator = sim::IntegratorKind::kXpbd;
  params.solver_iterations = 4;
  const double four = model.SecondsPerStep(params, 1, 0);
  params.solver_iterations = 8;
  EXPECT_NEAR(model.SecondsPerStep(params, 1, 0) - four,
              64 * 24 * 4 * model.integrators[int(sim::IntegratorKind::kXpbd)].per_node_substep_iteration, 1e-15);
  EXPECT_DOUBLE_EQ(model.RealTimeFraction(params, 1, 0), model.SecondsPerStep(params, 1, 0) / params.dt);
}

// A pass's cost per node follows the nodes as a power: w_ref at the reference, times 2^g per
// doubling of the nodes.
TEST(CostModel, CollisionCostPerNodeGrowsAsAPowerOfTheNodes) {
  const CollisionCost cost{4e-8, 3072, 0.75};
  EXPECT_DOUBLE_EQ(cost.PerNodePass(3072), 4e-8);
  EXPECT_NEAR(cost.PerNodePass(4 * 3072), 4e-8 * std::pow(4.0, 0.75), 1e-20);
  EXPECT_NEAR(cost.PerNodePass(3072 / 4.0), 4e-8 * std::pow(0.25, 0.75), 1e-20);
}

}  // namespace
}  // namespace flagsim::model
