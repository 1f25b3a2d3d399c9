// Every integrator MakeIntegrator makes: its order of convergence, its stability limit, pinned
// nodes, thread-count invariance.
#include "sim/integrator.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "lab/trajectory.hpp"
#include "sim/simulation.hpp"

namespace flagsim::sim {
namespace {

/// A small, soft, well damped flag in a steady wind, so that every explicit method (explicit
/// Euler included) is stable at the steps below and the errors are far above rounding.
lab::Trial SoftFlag(IntegratorKind kind) {
  lab::Trial trial;
  trial.params.cols = 6;
  trial.params.rows = 5;
  trial.params.stiffness = 200;
  trial.params.shear_stiffness = 20;
  trial.params.bend_stiffness = 2;
  trial.params.damping = 0.5;
  trial.params.integrator = kind;
  trial.wind = WindSettings{{3.0, 0.0, 2.0}, 0.0, 0.0};
  trial.horizon = 0.1;
  return trial;
}

struct OrderCase {
  IntegratorKind kind;
  double order;
};

class OrderTest : public ::testing::TestWithParam<OrderCase> {};

// Errors at N, 2N and 4N substeps against RK4 at 64 times finer; the slope of log error against
// log step between the two finest runs is the order. The reference has converged: halving its
// step changes it by far less than the smallest error measured.
TEST_P(OrderTest, ErrorFallsAtTheMethodsOrder) {
  constexpr int kCoarse = 64;
  const lab::Trial trial = SoftFlag(GetParam().kind);
  const lab::Trial reference_trial = SoftFlag(IntegratorKind::kRk4);
  const ClothState<double> reference = lab::RunFixed<double>(reference_trial, 4 * kCoarse * 64);
  const double reference_error =
      lab::RmsDistance(reference, lab::RunFixed<double>(reference_trial, 4 * kCoarse * 32));
  double errors[3];
  for (int k = 0; k < 3; ++k)
    errors[k] = lab::RmsDistance(lab::RunFixed<double>(trial, kCoarse << k), reference);
  EXPECT_LT(reference_error, 1e-3 * errors[2]);
  const double slope = std::log2(errors[1] / errors[2]);
  EXPECT_NEAR(slope, GetParam().order, 0.25)
      << "errors " << errors[0] << " " << errors[1] << " " << errors[2];
  EXPECT_GT(std::log2(errors[0] / errors[1]), GetParam().order - 0.5);
}

// XPBD and projective dynamics at a fixed iteration count approximate implicit Euler: first
// order too (projective dynamics with its damping split, explicit across springs).
INSTANTIATE_TEST_SUITE_P(All, OrderTest,
                         ::testing::Values(OrderCase{IntegratorKind::kExplicitEuler, 1},
                                           OrderCase{IntegratorKind::kSymplecticEuler, 1},
                                           OrderCase{IntegratorKind::kVelocityVerlet, 2},
                                           OrderCase{IntegratorKind::kRk4, 4},
                                           OrderCase{IntegratorKind::kXpbd, 1},
                                           OrderCase{IntegratorKind::kImplicitEuler, 1},
                                           OrderCase{IntegratorKind::kProjectiveDynamics, 1}),
                         [](const auto& info) { return IntegratorName(info.param.kind); });

class EveryIntegrator : public ::testing::TestWithParam<IntegratorKind> {};

// The largest stable step the integrator claims, from the grid's frequency bound, is stable;
// four times it is not (for the explicit methods: the bound is not wildly conservative).
TEST_P(EveryIntegrator, ClaimedStableStepIsStable) {
  lab::Trial trial = SoftFlag(GetParam());
  trial.params.damping = 0.05;  // lightly damped: the hard case
  trial.params.cols = 12;
  trial.params.rows = 8;
  trial.horizon = 2.0;
  const ClothModel<double> model = BuildClothModel<double>(trial.params);
  const double limit = MakeIntegrator<double>(GetParam())
                           ->StableStep(EstimateFrequencyBound(model, AirFriction(trial.params)));
  if (!std::isfinite(limit)) {  // unconditionally stable: try a large step
    const ClothState<double> state = lab::RunFixed<double>(trial, 20);
    EXPECT_TRUE(lab::StateIsSound(state));
    return;
  }
  const auto steps_for = [&](double h) { return static_cast<int>(std::ceil(trial.horizon / h)); };
  EXPECT_TRUE(lab::StateIsSound(lab::RunFixed<double>(trial, steps_for(limit)))) << "h = " << limit;
  EXPECT_FALSE(lab::StateIsSound(lab::RunFixed<double>(trial, steps_for(4 * limit)))) << "h = " << 4 * limit;
}

// The hoist edge stays where it was pinned, at zero velocity.
TEST_P(EveryIntegrator, PinnedNodesNeverMove) {
  lab::Trial trial = SoftFlag(GetParam());
  const ClothModel<double> model = BuildClothModel<double>(trial.params);
  const ClothState<double> state = lab::RunFixed<double>(trial, 400);
  for (int i = 0; i < model.num_nodes(); ++i) {
    if (!model.pinned(i)) continue;
    EXPECT_EQ(state.x[i], model.rest_x[i]);
    EXPECT_EQ(state.y[i], model.rest_y[i]);
    EXPECT_EQ(state.z[i], model.rest_z[i]);
    EXPECT_EQ(state.vx[i], 0.0);
  }
}

// The server's flag (float, gusts on, automatic substeps) gives the same bits at 1, 2 and 3
// threads.
TEST_P(EveryIntegrator, SameStateAtAnyThreadCount) {
  std::map<int, uint64_t> hashes;
  for (const int threads : {1, 2, 3}) {
    SimParams params;
    params.cols = 20;
    params.rows = 14;
    params.integrator = GetParam();
    params.threads = threads;
    Simulation<float> simulation(params, WindSettings{{8.0, 0.0, 2.0}, 0.3, 0.0}, 7);
    for (int step = 0; step < 40; ++step) simulation.Step();
    hashes[threads] = simulation.Hash();
  }
  EXPECT_EQ(hashes[1], hashes[2]);
  EXPECT_EQ(hashes[1], hashes[3]);
}

INSTANTIATE_TEST_SUITE_P(All, EveryIntegrator,
                         ::testing::Values(IntegratorKind::kSymplecticEuler, IntegratorKind::kSeed,
                                           IntegratorKind::kExplicitEuler, IntegratorKind::kVelocityVerlet,
                                           IntegratorKind::kRk4, IntegratorKind::kXpbd,
                                           IntegratorKind::kImplicitEuler,
                                           IntegratorKind::kProjectiveDynamics),
                         [](const auto& info) { return IntegratorName(info.param); });

TEST(IntegratorNames, OnePerKindInOrder) {
  for (size_t i = 0; i < IntegratorNames().size(); ++i) {
    EXPECT_NE(MakeIntegrator<float>(static_cast<IntegratorKind>(i)), nullptr) << IntegratorNames()[i];
  }
}

}  // namespace
}  // namespace flagsim::sim
