#include "server/sim/forces.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/sim/sim_test_util.hpp"

namespace flagsim::sim {
namespace {

using testing::Isolated;
using testing::NoWind;

/// Two nodes and one structural spring along x: the smallest model the force loops accept. Its
/// compression stiffness is k_compressed, or k when that is negative.
ClothModel<double> OneSpring(double k, double c, double rest, double k_compressed = -1) {
  ClothModel<double> model;
  model.cols = 2;
  model.rows = 1;
  model.dx = rest;
  model.dy = 1;
  model.families = {{SpringKind::kStructural, 0, 1, rest, k, c, k_compressed < 0 ? k : k_compressed}};
  model.mass = {1.0, 1.0};
  model.inverse_mass = {1.0, 1.0};
  model.rest_x = {0, rest};
  model.rest_y = {0, 0};
  model.rest_z = {0, 0};
  return model;
}

TEST(Forces, OneSpringPullsBothEndsEquallyAndOppositely) {
  const double k = 50, rest = 0.2;
  const ClothModel<double> model = OneSpring(k, 0, rest);
  ClothState<double> state = RestState(model);
  state.x[1] = 0.3;  // stretched 0.1 along x
  state.y[1] = 0.0;
  ForceEvaluator<double> evaluator;
  NodeForces<double> forces;
  evaluator.Evaluate(model, Isolated(), WindField(NoWind()), state, 0, &forces);
  EXPECT_NEAR(forces.x[0], k * 0.1, 1e-12);  // k (|d| - L) towards the other node
  EXPECT_NEAR(forces.x[1], -k * 0.1, 1e-12);
  EXPECT_EQ(forces.y[0], 0);
  EXPECT_EQ(forces.z[1], 0);
}

TEST(Forces, ACompressedSpringPushesWithItsCompressionStiffness) {
  // Choi and Ko 2002's split: k when longer than L, k_c when shorter.
  const double k = 50, k_compressed = 5, rest = 0.2;
  const ClothModel<double> model = OneSpring(k, 0, rest, k_compressed);
  ClothState<double> state = RestState(model);
  ForceEvaluator<double> evaluator;
  NodeForces<double> forces;
  state.x[1] = 0.15;  // compressed by 0.05
  evaluator.Evaluate(model, Isolated(), WindField(NoWind()), state, 0, &forces);
  EXPECT_NEAR(forces.x[0], -k_compressed * 0.05, 1e-12);  // pushed away from the other node
  EXPECT_NEAR(forces.x[1], k_compressed * 0.05, 1e-12);
  state.x[1] = 0.25;  // stretched by 0.05: the full stiffness
  evaluator.Evaluate(model, Isolated(), WindField(NoWind()), state, 0, &forces);
  EXPECT_NEAR(forces.x[0], k * 0.05, 1e-12);
  state.x[1] = rest;  // at its rest length: no force in either regime
  evaluator.Evaluate(model, Isolated(), WindField(NoWind()), state, 0, &forces);
  EXPECT_NEAR(forces.x[0], 0.0, 1e-12);
}

TEST(Forces, SpringForceActsAlongTheSpringIn3D) {
  const double k = 10, rest = 1.0;
  const ClothModel<double> model = OneSpring(k, 0, rest);
  ClothState<double> state = RestState(model);
  state.x[1] = 1.0;
  state.y[1] = 2.0;
  state.z[1] = 2.0;  // |d| = 3
  ForceEvaluator<double> evaluator;
  NodeForces<double> forces;
  evaluator.Evaluate(model, Isolated(), WindField(NoWind()), state, 0, &forces);
  const double magnitude = k * (3.0 - rest);
  EXPECT_NEAR(forces.x[0], magnitude / 3, 1e-12);
  EXPECT_NEAR(forces.y[0], 2 * magnitude / 3, 1e-12);
  EXPECT_NEAR(forces.z[0], 2 * magnitude / 3, 1e-12);
}

TEST(Forces, SpringDampingOpposesTheClosingSpeedOnly) {
  const double c = 3, rest = 1.0;
  const ClothModel<double> model = OneSpring(0, c, rest);
  ClothState<double> state = RestState(model);
  state.vx[1] = 2.0;  // separating along the spring
  state.vy[1] = 5.0;  // sliding across it: no damping
  ForceEvaluator<double> evaluator;
  NodeForces<double> forces;
  evaluator.Evaluate(model, Isolated(), WindField(NoWind()), state, 0, &forces);
  EXPECT_NEAR(forces.x[0], c * 2.0, 1e-12);
  EXPECT_NEAR(forces.x[1], -c * 2.0, 1e-12);
  EXPECT_NEAR(forces.y[1], 0, 1e-12);
}

TEST(Forces, GravityAndFrictionPerNode) {
  SimParams params = Isolated();
  params.forces.gravity = 9.81;
  params.forces.friction = 0.5;
  const ClothModel<double> model = OneSpring(0, 0, 1.0);
  ClothState<double> state = RestState(model);
  state.vz[1] = 4.0;
  ForceEvaluator<double> evaluator;
  NodeForces<double> forces;
  evaluator.Evaluate(model, params, WindField(NoWind()), state, 0, &forces);
  EXPECT_NEAR(forces.y[0], -9.81, 1e-12);
  EXPECT_NEAR(forces.z[1], -0.5 * 4.0, 1e-12);
}

TEST(Forces, WindOnAFlatFlagIsCTimesAreaTimesNormalWind) {
  // Flat flag in the x-y plane (normal +z); wind w: total force C A n (n . w) = C A w_z z^.
  SimParams params = Isolated();
  params.imperfection = 0;  // exactly flat
  params.forces.wind_coefficient = 1.7;
  params.forces.stiffness = 1;  // at rest: no spring force anyway
  const ClothModel<double> model = BuildClothModel<double>(params);
  const ClothState<double> state = RestState(model);
  const WindField wind(WindSettings{{3.0, -1.0, 2.0}, 0, 0});
  ForceEvaluator<double> evaluator;
  NodeForces<double> forces;
  evaluator.Evaluate(model, params, wind, state, 0, &forces);
  double total[3] = {0, 0, 0};
  for (int i = 0; i < model.num_nodes(); ++i) {
    total[0] += forces.x[i];
    total[1] += forces.y[i];
    total[2] += forces.z[i];
  }
  const double area = params.width * params.height;
  EXPECT_NEAR(total[0], 0, 1e-9);
  EXPECT_NEAR(total[1], 0, 1e-9);
  EXPECT_NEAR(total[2], 1.7 * area * 2.0, 1e-9);
  // An interior node carries the wind of its six triangles, a third each: one cell's worth.
  const int interior = model.index(5, 5);
  EXPECT_NEAR(forces.z[interior], 1.7 * model.dx * model.dy * 2.0, 1e-12);
}

TEST(Forces, RelativeWindSubtractsTheClothVelocity) {
  SimParams params = Isolated();
  params.imperfection = 0;  // flat, so that every node carries the same share of face velocity
  params.forces.wind_coefficient = 1.0;
  params.relative_wind = true;
  const ClothModel<double> model = BuildClothModel<double>(params);
  ClothState<double> state = RestState(model);
  for (double& v : state.vz) v = 2.0;  // moving with the wind: no relative wind
  const WindField wind(WindSettings{{0, 0, 2.0}, 0, 0});
  ForceEvaluator<double> evaluator;
  NodeForces<double> forces;
  evaluator.Evaluate(model, params, wind, state, 0, &forces);
  for (int i = 0; i < model.num_nodes(); ++i) EXPECT_NEAR(forces.z[i], 0, 1e-12);
}

// Leaving a term out is the same, bit for bit, as evaluating a flag that lacks it: springs as a
// model without spring families, bending as one without bending stiffness, friction as
// parameters with none.
TEST(Forces, TermsLeftOutAreAsIfTheFlagLackedThem) {
  SimParams params;
  params.cols = 13;
  params.rows = 9;
  const ClothModel<float> model = BuildClothModel<float>(params);
  ClothState<float> state = RestState(model);
  for (int i = 0; i < model.num_nodes(); ++i) {
    state.z[i] = 0.05f * std::sin(0.37f * i);
    state.vy[i] = -0.3f * std::cos(0.23f * i);
  }
  const WindField wind(WindSettings{{6, 0, 1.5}, 0.3, 0});
  ClothModel<float> springless = model, unbending = model;
  springless.families.clear();
  unbending.bending_stiffness = 0;
  ClothModel<float> bare = springless;
  bare.bending_stiffness = 0;
  SimParams frictionless = params;
  frictionless.forces.friction = 0;
  const struct {
    ForceTerms terms;
    const ClothModel<float>& lacking_model;
    const SimParams& lacking_params;
  } cases[] = {{Without(ForceTerms::kAll, ForceTerms::kSprings), springless, params},
               {Without(ForceTerms::kAll, ForceTerms::kBending), unbending, params},
               {ForceTerms::kGravity | ForceTerms::kWind, bare, frictionless}};
  for (const auto& each : cases) {
    ForceEvaluator<float> evaluator, reference_evaluator;
    NodeForces<float> forces, reference;
    evaluator.Evaluate(model, params, wind, state, 0.4, &forces, each.terms);
    reference_evaluator.Evaluate(each.lacking_model, each.lacking_params, wind, state, 0.4, &reference);
    EXPECT_EQ(forces.x, reference.x);
    EXPECT_EQ(forces.y, reference.y);
    EXPECT_EQ(forces.z, reference.z);
  }
}

TEST(Forces, SameForcesAtAnyThreadCount) {
  SimParams params;
  params.cols = 37;
  params.rows = 29;
  const ClothModel<float> model = BuildClothModel<float>(params);
  ClothState<float> state = RestState(model);
  for (int i = 0; i < model.num_nodes(); ++i) {  // a crumpled, moving state
    state.z[i] = 0.05f * std::sin(0.37f * i);
    state.vx[i] = 0.2f * std::cos(0.11f * i);
  }
  const WindField wind(WindSettings{{6, 0, 1.5}, 0.3, 0});
  NodeForces<float> reference;
  ForceEvaluator<float> evaluator;
  evaluator.Evaluate(model, params, wind, state, 0.7, &reference);
  for (int threads : {2, 3, 7}) {
    params.threads = threads;
    NodeForces<float> forces;
    evaluator.Evaluate(model, params, wind, state, 0.7, &forces);
    EXPECT_EQ(forces.x, reference.x) << threads << " threads";
    EXPECT_EQ(forces.y, reference.y) << threads << " threads";
    EXPECT_EQ(forces.z, reference.z) << threads << " threads";
  }
}

}  // namespace
}  // namespace flagsim::sim
