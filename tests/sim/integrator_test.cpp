// Every integrator MakeIntegrator makes: its order of convergence, its stability limit, pinned
// nodes, thread-count invariance.
#include "server/sim/integrator.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

#include "lab/trajectory.hpp"
#include "server/sim/simulation.hpp"
#include "tests/sim/sim_test_util.hpp"

namespace flagsim::sim {
namespace {

/// A small, soft, well damped flag in a steady wind, so that every explicit method (explicit
/// Euler included) is stable at the steps below and the errors are far above rounding.
lab::Trial SoftFlag(IntegratorKind kind) {
  lab::Trial trial;
  trial.params.cols = 6;
  trial.params.rows = 5;
  trial.params.forces.stiffness = 200;
  trial.params.forces.shear_stiffness = 20;
  trial.params.forces.bending_stiffness = 5e-5;
  trial.params.forces.damping = 0.5;
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
// step changes it by far less than the smallest error measured. The springs are as stiff in
// compression as in stretch: a spring crossing its rest length with another stiffness has a
// force whose derivative jumps there, so the motion is only twice differentiable in time at the
// crossings and a method of order p > 2 (RK4) no longer shows its order; the order of each method
// is a property of smooth forces.
TEST_P(OrderTest, ErrorFallsAtTheMethodsOrder) {
  constexpr int kCoarse = 64;
  lab::Trial trial = SoftFlag(GetParam().kind);
  lab::Trial reference_trial = SoftFlag(IntegratorKind::kRk4);
  trial.params.compression = reference_trial.params.compression = 1;
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
  trial.params.forces.damping = 0.05;  // lightly damped: the hard case
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
    params.min_nodes_per_thread = 1;  // share even a small flag among the threads
    Simulation<float> simulation(params, WindSettings{{8.0, 0.0, 2.0}, 0.3, 0.0}, 7);
    for (int step = 0; step < 40; ++step) simulation.Step();
    hashes[threads] = simulation.Hash();
  }
  EXPECT_EQ(hashes[1], hashes[2]);
  EXPECT_EQ(hashes[1], hashes[3]);
}

// Choi and Ko's split in every integrator: one vertical spring (k = 1000 N/m stretched,
// k_c = 100 N/m compressed, critically damped in compression) with one end pinned and 1 kg on
// the other comes to rest where its regime's stiffness carries the weight: hanging below its
// pinned end it stretches by m g / k; standing on it, it shortens by m g / k_c.
TEST_P(EveryIntegrator, ASpringRestsWhereItsRegimesStiffnessCarriesTheWeight) {
  const double k = 1000, k_compressed = 100, mass = 1, gravity = 9.81;
  for (const bool standing : {false, true}) {
    ClothModel<double> model;
    model.cols = 1;
    model.rows = 2;
    model.dx = 1;
    model.dy = 1;
    model.families = {{SpringKind::kStructural, 1, 0, 1.0, k, 20.0, k_compressed}};
    model.mass = {mass, mass};
    model.inverse_mass = standing ? std::vector<double>{1 / mass, 0} : std::vector<double>{0, 1 / mass};
    model.rest_x = {0, 0};
    model.rest_y = {1, 0};
    model.rest_z = {0, 0};
    SimParams params = testing::Isolated();
    params.forces.gravity = gravity;
    params.integrator = GetParam();
    const WindField wind(testing::NoWind());
    ForceEvaluator<double> evaluator;
    const auto integrator = MakeIntegrator<double>(GetParam());
    const double h = std::min(0.002, 0.8 * integrator->StableStep(EstimateFrequencyBound(model, 0.0)));
    ClothState<double> state = RestState(model);
    for (double t = 0; t < 8; t += h) integrator->Substep({model, params, wind, evaluator}, h, &state);
    const double length = state.y[0] - state.y[1];
    const double expected = standing ? 1 - mass * gravity / k_compressed : 1 + mass * gravity / k;
    EXPECT_NEAR(length, expected, 1e-9) << (standing ? "standing" : "hanging");
  }
}

/// A sheet held at both ends 10 % closer than its length (no gravity, no wind), so that it is
/// in compression, after 2 s of `kind` from rest: the largest |z| of its nodes, m, at the start
/// and at the end, and whether it stayed sound.
struct Buckling {
  double before = 0, after = 0;
  bool sound = false;
};
Buckling CompressedSheet(IntegratorKind kind, double imperfection) {
  SimParams params = testing::Isolated();
  params.cols = 12;
  params.rows = 8;
  params.forces.friction = kind == IntegratorKind::kSeed ? 0 : 1;  // the seed's friction is a fraction of F
  params.imperfection = imperfection;
  params.integrator = kind;
  ClothModel<double> model = BuildClothModel<double>(params);
  ClothState<double> state = RestState(model);
  Buckling result;
  for (int r = 0; r < model.rows; ++r) {
    model.inverse_mass[model.index(r, model.cols - 1)] = 0;  // the fly edge held too
    for (int c = 0; c < model.cols; ++c) {
      state.x[model.index(r, c)] *= 0.9;
      result.before = std::max(result.before, std::abs(state.z[model.index(r, c)]));
    }
  }
  const WindField wind(testing::NoWind());
  ForceEvaluator<double> evaluator;
  const auto integrator = MakeIntegrator<double>(kind);
  const double h = std::min(0.002, 0.8 * integrator->StableStep(EstimateFrequencyBound(model, 0.0)));
  for (double t = 0; t < 2; t += h) integrator->Substep({model, params, wind, evaluator}, h, &state);
  result.sound = lab::StateIsSound(state);
  for (const double z : state.z) result.after = std::max(result.after, std::abs(z));
  return result;
}

// Started exactly flat, every force stays in the plane and the sheet cannot leave it, however soft
// in compression; from the model's 1 mm imperfection it buckles out of its plane, by far more.
TEST_P(EveryIntegrator, ASheetCompressedInItsPlaneBucklesOutOfIt) {
  const Buckling flat = CompressedSheet(GetParam(), 0.0);
  EXPECT_TRUE(flat.sound);
  EXPECT_EQ(flat.after, 0.0);
  const Buckling imperfect = CompressedSheet(GetParam(), 1e-3);
  ASSERT_TRUE(imperfect.sound);
  EXPECT_NEAR(imperfect.before, 1e-3, 1e-12);
  EXPECT_GT(imperfect.after, 50 * imperfect.before)
      << "from " << imperfect.before << " m to " << imperfect.after << " m";
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
