#include "server/sim/conjugate_gradient.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "tests/sim/sim_test_util.hpp"

namespace flagsim::sim {
namespace {

/// The implicit-Euler system of a crumpled, moving 24 x 16 flag at h = 10 ms.
struct System {
  System() {
    SimParams params = testing::Isolated();
    params.cols = 24;
    params.rows = 16;
    params.forces.gravity = 9.81;
    params.forces.stiffness = 20000;
    model = BuildClothModel<double>(params);
    ClothState<double> state = RestState(model);
    std::mt19937 random(11);
    std::uniform_real_distribution<double> jitter(-1, 1);
    for (int i = 0; i < model.num_nodes(); ++i) {
      if (model.pinned(i)) continue;
      state.x[i] += 0.01 * jitter(random);
      state.z[i] += 0.05 * jitter(random);
      state.vz[i] = jitter(random);
    }
    ForceEvaluator<double> evaluator;
    NodeForces<double> forces;
    evaluator.Evaluate(model, params, WindField(testing::NoWind()), state, 0, &forces);
    jacobian.Assemble(model, state, forces, 0.01, params.forces.friction, 1, &b);
  }

  /// |b - A x| / |b|, computed afresh.
  double RelativeResidual(const NodeVectors<double>& x) const {
    NodeVectors<double> product;
    product.Resize(model.num_nodes());
    for (int r = 0; r < model.rows; ++r) jacobian.Multiply(x, r, &product);
    double residual = 0, norm = 0;
    for (int i = 0; i < model.num_nodes(); ++i) {
      residual += std::pow(b.x[i] - product.x[i], 2) + std::pow(b.y[i] - product.y[i], 2) +
                  std::pow(b.z[i] - product.z[i], 2);
      norm += b.x[i] * b.x[i] + b.y[i] * b.y[i] + b.z[i] * b.z[i];
    }
    return std::sqrt(residual / norm);
  }

  ClothModel<double> model;
  SpringJacobian<double> jacobian;
  NodeVectors<double> b;
};

TEST(ConjugateGradient, ConvergesToTheTolerance) {
  System system;
  ConjugateGradient<double> solver;
  for (double tolerance : {1e-3, 1e-8}) {
    NodeVectors<double> x;
    const SolveReport report = solver.Solve(system.jacobian, system.b, tolerance, 1000, 1, &x);
    EXPECT_GT(report.iterations, 1);
    EXPECT_LE(report.relative_residual, tolerance);
    EXPECT_LE(system.RelativeResidual(x), 1.01 * tolerance);
  }
}

TEST(ConjugateGradient, StopsAtTheIterationCap) {
  System system;
  ConjugateGradient<double> solver;
  NodeVectors<double> x;
  const SolveReport report = solver.Solve(system.jacobian, system.b, 1e-12, 3, 1, &x);
  EXPECT_EQ(report.iterations, 3);
  EXPECT_GT(report.relative_residual, 1e-12);
  EXPECT_NEAR(system.RelativeResidual(x), report.relative_residual, 1e-9);
}

TEST(ConjugateGradient, StartsFromTheGuessAndKeepsPinnedEntriesAtZero) {
  System system;
  ConjugateGradient<double> solver;
  NodeVectors<double> cold, warm;
  const SolveReport first = solver.Solve(system.jacobian, system.b, 1e-6, 1000, 1, &cold);
  warm = cold;
  const SolveReport again = solver.Solve(system.jacobian, system.b, 1e-6, 1000, 1, &warm);
  EXPECT_EQ(again.iterations, 0);  // the answer itself is a converged guess
  EXPECT_GT(first.iterations, 0);
  for (int r = 0; r < system.model.rows; ++r) {
    const int i = system.model.index(r, 0);
    EXPECT_EQ(cold.x[i], 0.0);
    EXPECT_EQ(cold.y[i], 0.0);
    EXPECT_EQ(cold.z[i], 0.0);
  }
}

TEST(ConjugateGradient, ZeroRightHandSideGivesZero) {
  System system;
  system.b.SetZero();
  ConjugateGradient<double> solver;
  NodeVectors<double> x;
  x.Resize(system.model.num_nodes());
  x.x.assign(x.x.size(), 1.0);
  const SolveReport report = solver.Solve(system.jacobian, system.b, 1e-6, 1000, 1, &x);
  EXPECT_EQ(report.iterations, 0);
  for (double value : x.x) EXPECT_EQ(value, 0.0);
}

}  // namespace
}  // namespace flagsim::sim
