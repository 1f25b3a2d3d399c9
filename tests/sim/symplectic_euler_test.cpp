#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "server/sim/integrator.hpp"
#include "tests/sim/sim_test_util.hpp"

namespace flagsim::sim {
namespace {

using testing::Isolated;
using testing::NoWind;

struct Rig {
  explicit Rig(const SimParams& params_in, ClothModel<double> model_in)
      : params(params_in),
        model(std::move(model_in)),
        wind(NoWind()),
        integrator(MakeIntegrator<double>(params.integrator)),
        state(RestState(model)) {}
  void Run(int substeps, double h) {
    const StepContext<double> context{model, params, wind, evaluator};
    for (int i = 0; i < substeps; ++i) integrator->Substep(context, h, &state);
  }
  SimParams params;
  ClothModel<double> model;
  WindField wind;
  ForceEvaluator<double> evaluator;
  std::unique_ptr<Integrator<double>> integrator;
  ClothState<double> state;
};

TEST(SymplecticEuler, FreeFallOfAnUnpinnedFlagFollowsGravity) {
  // Internal forces cancel, so the centre of mass falls as one body. Symplectic Euler's exact
  // discrete solution: v_n = -g n h, y_n = y_0 - g h^2 n (n + 1) / 2 = y_0 - g t (t + h) / 2.
  SimParams params = Isolated();
  params.forces.gravity = 9.81;
  ClothModel<double> model = BuildClothModel<double>(params);
  testing::Unpin(&model);
  Rig rig(params, model);
  const double y0 = testing::CentreOfMass(rig.model, rig.state)[1];
  const double h = 1e-4;
  const int n = 5000;
  rig.Run(n, h);
  const double t = n * h;
  EXPECT_NEAR(testing::CentreOfMass(rig.model, rig.state)[1], y0 - 9.81 * t * (t + h) / 2, 1e-9);
  EXPECT_NEAR(rig.state.time, t, 1e-12);
}

TEST(SymplecticEuler, MomentumIsConservedWithoutExternalForces) {
  ClothModel<double> model = BuildClothModel<double>(Isolated());
  testing::Unpin(&model);
  Rig rig(Isolated(), model);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> jitter(-0.5, 0.5);
  for (int i = 0; i < model.num_nodes(); ++i) {
    rig.state.z[i] += 0.01 * jitter(random);
    rig.state.vx[i] = jitter(random);
    rig.state.vy[i] = jitter(random);
    rig.state.vz[i] = jitter(random);
  }
  const auto before = testing::Momentum(rig.model, rig.state);
  rig.Run(2000, 1e-4);
  const auto after = testing::Momentum(rig.model, rig.state);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(after[k], before[k], 1e-12);
  EXPECT_GT(testing::SpringEnergy(rig.model, rig.state), 0);  // the springs did work
}

/// Node 1 (1 kg) on a spring along x (L = 1 m; k when stretched, k_c when compressed) to pinned
/// node 0, released from 0.1 m of stretch and stepped at h = 1e-4 s for 6 s: the times it
/// crosses its rest length, upward (into stretch) and downward (into compression).
struct Crossings {
  std::vector<double> up, down;
};
Crossings OneSpringCrossings(double k, double k_compressed) {
  ClothModel<double> model;
  model.cols = 2;
  model.rows = 1;
  model.dx = 1.0;
  model.dy = 1.0;
  model.families = {{SpringKind::kStructural, 0, 1, 1.0, k, 0.0, k_compressed}};
  model.mass = {1.0, 1.0};
  model.inverse_mass = {0.0, 1.0};
  model.rest_x = {0.0, 1.0};
  model.rest_y = {0.0, 0.0};
  model.rest_z = {0.0, 0.0};
  Rig rig(Isolated(), model);
  rig.state.x[1] = 1.1;
  const double h = 1e-4;
  Crossings crossings;
  double previous = rig.state.x[1] - 1.0;
  for (int i = 0; i < 60000; ++i) {
    rig.Run(1, h);
    const double now = rig.state.x[1] - 1.0;
    const double when = rig.state.time - h * now / (now - previous);
    if (previous < 0 && now >= 0) crossings.up.push_back(when);
    if (previous >= 0 && now < 0) crossings.down.push_back(when);
    previous = now;
  }
  EXPECT_EQ(rig.state.x[0], 0.0);  // the pinned end never moved
  return crossings;
}

TEST(SymplecticEuler, OneSpringOscillatesAtItsNaturalPeriod) {
  // As stiff in compression as in stretch (k = 40 N/m): T = 2 pi sqrt(m / k).
  const Crossings crossings = OneSpringCrossings(40.0, 40.0);
  ASSERT_GE(crossings.up.size(), 3u);
  const double period = (crossings.up.back() - crossings.up.front()) / (crossings.up.size() - 1);
  EXPECT_NEAR(period, 2 * M_PI * std::sqrt(1.0 / 40.0), 1e-4);
}

TEST(SymplecticEuler, ASpringSoftInCompressionSpendsLongerCompressed) {
  // k = 40 N/m stretched, k_c = 10 N/m compressed (compression 0.25): each half of the cycle is
  // half a period of its own regime, so the stretched half stays pi sqrt(m / k), as stiff as
  // before, and the compressed half is pi sqrt(m / k_c), twice as long.
  const double k = 40.0, k_compressed = 10.0;
  const Crossings crossings = OneSpringCrossings(k, k_compressed);
  ASSERT_GE(crossings.up.size(), 3u);
  ASSERT_GE(crossings.down.size(), crossings.up.size());
  const double period = (crossings.up.back() - crossings.up.front()) / (crossings.up.size() - 1);
  EXPECT_NEAR(period, M_PI * (std::sqrt(1.0 / k) + std::sqrt(1.0 / k_compressed)), 1e-4);
  for (size_t i = 0; i + 1 < crossings.up.size(); ++i) {
    const double stretched = crossings.down[i + 1] - crossings.up[i];  // the first down is at release
    EXPECT_NEAR(stretched, M_PI * std::sqrt(1.0 / k), 1e-4) << "cycle " << i;
  }
}

TEST(SymplecticEuler, StableStepIsTwoOverOmegaWithoutDamping) {
  const auto integrator = MakeIntegrator<double>(IntegratorKind::kSymplecticEuler);
  EXPECT_DOUBLE_EQ(integrator->StableStep({100.0 * 100.0, 0.0}), 2.0 / 100.0);
  // with damping g the limit shrinks: h^2 w^2 + 2 h g = 4 at the limit
  const double h = integrator->StableStep({100.0 * 100.0, 30.0});
  EXPECT_NEAR(h * h * 1e4 + 2 * h * 30.0, 4.0, 1e-12);
  EXPECT_LT(h, 0.02);
}

TEST(SeedScheme, FrictionScalesTheForce) {
  // The seed's F_fric = -mu F: a free node under gravity alone falls at (1 - mu) g.
  SimParams params = Isolated();
  params.forces.gravity = 10;
  params.forces.friction = 0.25;
  params.integrator = IntegratorKind::kSeed;
  params.imperfection = 0;  // flat: every spring at its rest length, no spring force
  ClothModel<double> model = BuildClothModel<double>(params);
  testing::Unpin(&model);
  Rig rig(params, model);
  rig.Run(1, 0.01);
  EXPECT_NEAR(rig.state.vy[5], -0.75 * 10 * 0.01, 1e-10);
}

}  // namespace
}  // namespace flagsim::sim
