#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "server/sim/integrator.hpp"
#include "server/sim/simulation.hpp"
#include "tests/sim/sim_test_util.hpp"

namespace flagsim::sim {
namespace {

using testing::NoWind;

SimParams Projective() {
  SimParams params;
  params.integrator = IntegratorKind::kProjectiveDynamics;
  return params;
}

TEST(ProjectiveDynamics, HangingFlagComesToRestInForceBalance) {
  // A fixed point of the local/global iteration with v = 0 is a zero of springs + gravity. The
  // flag is flat with springs as stiff in compression as in stretch, so that it sags in its plane
  // to one pose well within the 30 s: buckled (compression < 1), it falls into folds whose last
  // motions the iteration follows slowly (each iteration shrinks a compressed spring's error by a
  // factor of up to 1 - k_c / k), still moving after 30 s even at 40 iterations. The compressed
  // regime's fixed point is checked on one spring in integrator_test.cpp.
  SimParams params = Projective();
  params.cols = 16;
  params.rows = 12;
  params.dt = 1.0 / 60;
  params.forces.friction = 2;
  params.compression = 1;
  params.imperfection = 0;
  Simulation<double> simulation(params, NoWind());
  for (int i = 0; i < 1800; ++i) simulation.Step();  // 30 s
  const ClothModel<double>& model = simulation.model();
  ClothState<double> state = simulation.state();
  EXPECT_LT(testing::KineticEnergy(model, state), 1e-12);
  EXPECT_LT(state.y[model.num_nodes() - 1], model.rest_y[model.num_nodes() - 1] - 0.02);  // it sags

  state.vx = state.vy = state.vz = std::vector<double>(model.num_nodes(), 0.0);
  ForceEvaluator<double> evaluator;
  NodeForces<double> forces;
  evaluator.Evaluate(model, params, simulation.wind(), state, state.time, &forces);
  double worst = 0;  // the largest net force, in units of the node's weight
  for (int i = 0; i < model.num_nodes(); ++i) {
    if (model.pinned(i)) continue;
    const double net =
        std::sqrt(forces.x[i] * forces.x[i] + forces.y[i] * forces.y[i] + forces.z[i] * forces.z[i]);
    worst = std::max(worst, net / (model.mass[i] * params.forces.gravity));
  }
  EXPECT_LT(worst, 1e-6);
}

TEST(ProjectiveDynamics, FreeFlagFallsWithImplicitFriction) {
  // Springs at rest length stay there, so every node steps v' = (v - g h) / (1 + h mu).
  SimParams params = Projective();
  params.imperfection = 0;  // flat: every spring at its rest length
  params.forces.friction = 0.5;
  params.forces.wind_coefficient = 0;
  ClothModel<double> model = BuildClothModel<double>(params);
  testing::Unpin(&model);
  const WindField wind(NoWind());
  ForceEvaluator<double> evaluator;
  const auto integrator = MakeIntegrator<double>(IntegratorKind::kProjectiveDynamics);
  ClothState<double> state = RestState(model);
  const double h = 0.01;
  double v = 0, y = state.y[7];
  for (int step = 0; step < 50; ++step) {
    integrator->Substep({model, params, wind, evaluator}, h, &state);
    v = (v - params.forces.gravity * h) / (1 + h * params.forces.friction);
    y += h * v;
  }
  EXPECT_NEAR(state.vy[7], v, 1e-9);
  EXPECT_NEAR(state.y[7], y, 1e-9);
  EXPECT_NEAR(state.vx[7], 0.0, 1e-9);
}

TEST(ProjectiveDynamics, StiffFlagAtLargeStepsNeverExceedsItsInitialEnergy) {
  SimParams params = Projective();
  params.cols = 64;
  params.rows = 48;
  params.forces.stiffness = 1e5;
  params.dt = 1.0 / 60;
  Simulation<double> simulation(params, NoWind());
  const auto energy = [&] {
    const auto& model = simulation.model();
    const auto& state = simulation.state();
    double height = 0;
    for (int i = 0; i < model.num_nodes(); ++i) height += model.mass[i] * params.forces.gravity * state.y[i];
    return testing::KineticEnergy(model, state) + testing::SpringEnergy(model, state) + height;
  };
  // Truncated iterations let the sag breathe slowly, so energy is not monotone; it must stay
  // below the start's (the flag at rest, flat) for as long as the flag moves.
  const double start = energy();
  for (int step = 0; step < 120; ++step) {
    simulation.Step();
    const double now = energy();
    ASSERT_TRUE(std::isfinite(now));
    ASSERT_LT(now, start) << "step " << step;
  }
  EXPECT_EQ(simulation.substeps(), 1);
  EXPECT_EQ(simulation.recoveries(), 0);
}

TEST(ProjectiveDynamics, SameHashAtAnyThreadCount) {
  uint64_t reference = 0;
  for (int threads : {1, 2, 3}) {
    SimParams params = Projective();
    params.threads = threads;
    params.min_nodes_per_thread = 1;  // share even a small flag among the threads
    Simulation<float> simulation(params, WindSettings{});
    for (int i = 0; i < 40; ++i) simulation.Step();
    if (threads == 1) reference = simulation.Hash();
    EXPECT_EQ(simulation.Hash(), reference) << threads << " threads";
  }
}

TEST(ProjectiveDynamics, RefactorisesWhenTheStepOrTheSpringsChange) {
  // A step after a change must equal a fresh integrator's step: the cached factorisation of
  // the old matrix must not be reused.
  SimParams params = Projective();
  ClothModel<double> model = BuildClothModel<double>(params);
  const WindField wind(WindSettings{});
  ForceEvaluator<double> evaluator;
  ClothState<double> state = RestState(model);
  const auto reused = MakeIntegrator<double>(IntegratorKind::kProjectiveDynamics);
  const auto expect_fresh = [&](double h, const char* what) {
    ClothState<double> fresh = state;
    MakeIntegrator<double>(IntegratorKind::kProjectiveDynamics)
        ->Substep({model, params, wind, evaluator}, h, &fresh);
    reused->Substep({model, params, wind, evaluator}, h, &state);
    EXPECT_EQ(StateHash(state), StateHash(fresh)) << what;
  };
  expect_fresh(0.004, "first step");
  expect_fresh(0.004, "same step");
  expect_fresh(0.002, "new step");
  params.forces.stiffness *= 3;
  SetMaterialConstants(params, &model);
  expect_fresh(0.002, "new stiffness");
  params.forces.friction = 1;
  expect_fresh(0.002, "new friction");
}

TEST(ProjectiveDynamics, StableStepIsUnbounded) {
  const auto integrator = MakeIntegrator<double>(IntegratorKind::kProjectiveDynamics);
  EXPECT_EQ(integrator->StableStep({1e12, 1e6}), std::numeric_limits<double>::infinity());
  EXPECT_EQ(IntegratorName(IntegratorKind::kProjectiveDynamics), "projective");
}

}  // namespace
}  // namespace flagsim::sim
