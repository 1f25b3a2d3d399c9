#include "server/sim/spring_jacobian.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "tests/sim/sim_test_util.hpp"

namespace flagsim::sim {
namespace {

using Dense = Eigen::MatrixXd;
using testing::NoWind;

/// A 5 x 4 flag stretched by 10 % (every spring longer than its rest length, so no clamping),
/// jittered out of plane and moving.
struct StretchedFlag {
  StretchedFlag() {
    params = testing::Isolated();
    params.cols = 5;
    params.rows = 4;
    params.forces.gravity = 9.81;
    params.forces.friction = 0.3;
    params.forces.damping = 0.4;
    model = BuildClothModel<double>(params);
    state = RestState(model);
    std::mt19937 random(3);
    std::uniform_real_distribution<double> jitter(-1, 1);
    for (int i = 0; i < model.num_nodes(); ++i) {  // pinned nodes too: every spring stretches
      state.x[i] *= 1.1;
      state.y[i] = params.pole_height - 1.1 * (params.pole_height - state.y[i]);
      state.z[i] += 1e-2 * jitter(random);
      state.vx[i] = jitter(random);
      state.vy[i] = jitter(random);
      state.vz[i] = jitter(random);
    }
  }

  /// F at (x, v) as one vector (x0, y0, z0, x1, ...).
  Eigen::VectorXd Forces(const ClothState<double>& at) {
    NodeForces<double> forces;
    evaluator.Evaluate(model, params, WindField(NoWind()), at, 0, &forces);
    Eigen::VectorXd f(3 * model.num_nodes());
    for (int i = 0; i < model.num_nodes(); ++i) f.segment<3>(3 * i) << forces.x[i], forces.y[i], forces.z[i];
    return f;
  }

  /// dF/dx (at v = 0, where the damping force vanishes for every x) or dF/dv, by central
  /// differences.
  Dense Derivative(bool by_velocity) {
    ClothState<double> at = state;
    if (!by_velocity) at.vx = at.vy = at.vz = std::vector<double>(model.num_nodes(), 0.0);
    const double step = 1e-6;
    Dense jacobian(3 * model.num_nodes(), 3 * model.num_nodes());
    for (int j = 0; j < 3 * model.num_nodes(); ++j) {
      std::vector<double>* coordinate[3] = {by_velocity ? &at.vx : &at.x, by_velocity ? &at.vy : &at.y,
                                            by_velocity ? &at.vz : &at.z};
      double& value = (*coordinate[j % 3])[j / 3];
      const double saved = value;
      value = saved + step;
      const Eigen::VectorXd plus = Forces(at);
      value = saved - step;
      const Eigen::VectorXd minus = Forces(at);
      value = saved;
      jacobian.col(j) = (plus - minus) / (2 * step);
    }
    return jacobian;
  }

  SimParams params;
  ClothModel<double> model;
  ClothState<double> state;
  ForceEvaluator<double> evaluator;
};

Eigen::VectorXd Flatten(const NodeVectors<double>& v) {
  Eigen::VectorXd flat(3 * v.x.size());
  for (size_t i = 0; i < v.x.size(); ++i) flat.segment<3>(3 * i) << v.x[i], v.y[i], v.z[i];
  return flat;
}

/// S: 1 on the free nodes' coordinates, 0 on the pinned nodes'.
Eigen::VectorXd FreeMask(const ClothModel<double>& model) {
  Eigen::VectorXd mask(3 * model.num_nodes());
  for (int i = 0; i < model.num_nodes(); ++i) mask.segment<3>(3 * i).setConstant(model.pinned(i) ? 0 : 1);
  return mask;
}

TEST(SpringJacobian, MatrixAndRightHandSideMatchFiniteDifferences) {
  StretchedFlag flag;
  const double h = 0.01;
  NodeForces<double> forces;
  flag.evaluator.Evaluate(flag.model, flag.params, WindField(NoWind()), flag.state, 0, &forces);
  SpringJacobian<double> jacobian;
  NodeVectors<double> rhs;
  jacobian.Assemble(flag.model, flag.state, forces, h, flag.params.forces.friction, 1, &rhs);

  const int n = 3 * flag.model.num_nodes();
  const Dense dfdx = flag.Derivative(false), dfdv = flag.Derivative(true);
  Eigen::VectorXd mass(n);
  for (int i = 0; i < flag.model.num_nodes(); ++i) mass.segment<3>(3 * i).setConstant(flag.model.mass[i]);
  const Eigen::VectorXd mask = FreeMask(flag.model);
  const Dense expected =
      mask.asDiagonal() * (Dense(mass.asDiagonal()) - h * dfdv - h * h * dfdx) * mask.asDiagonal();
  Eigen::VectorXd v(n);
  for (int i = 0; i < flag.model.num_nodes(); ++i)
    v.segment<3>(3 * i) << flag.state.vx[i], flag.state.vy[i], flag.state.vz[i];
  const Eigen::VectorXd expected_rhs = mask.asDiagonal() * (h * flag.Forces(flag.state) + h * h * dfdx * v);

  // A's columns, one unit vector at a time (on free nodes: the pinned columns are filtered out).
  NodeVectors<double> unit, product;
  unit.Resize(flag.model.num_nodes());
  product.Resize(flag.model.num_nodes());
  for (int j = 0; j < n; ++j) {
    if (mask[j] == 0) continue;
    unit.SetZero();
    (j % 3 == 0 ? unit.x : j % 3 == 1 ? unit.y : unit.z)[j / 3] = 1;
    for (int r = 0; r < flag.model.rows; ++r) jacobian.Multiply(unit, r, &product);
    EXPECT_LT((Flatten(product) - expected.col(j)).norm(), 1e-6 * expected.col(j).norm()) << "column " << j;
  }
  EXPECT_LT((Flatten(rhs) - expected_rhs).norm(), 1e-6 * expected_rhs.norm());
}

TEST(SpringJacobian, CompressedSpringKeepsOnlyItsAxialStiffness) {
  // One spring along x compressed to half its rest length: the exact transverse stiffness
  // k_c (1 - L/|d|) would be negative; clamped, a transverse push meets only the mass. Along the
  // spring it is the compression stiffness k_c = 10 N/m, not the stretch stiffness k = 100 N/m.
  ClothModel<double> model;
  model.cols = 2;
  model.rows = 1;
  model.dx = 1;
  model.dy = 1;
  model.families = {{SpringKind::kStructural, 0, 1, 1.0, 100.0, 0.0, 10.0}};
  model.mass = {1.0, 2.0};
  model.inverse_mass = {0.0, 0.5};
  model.rest_x = {0, 1};
  model.rest_y = {0, 0};
  model.rest_z = {0, 0};
  ClothState<double> state = RestState(model);
  state.x[1] = 0.5;
  NodeForces<double> forces{{0, 0}, {0, 0}, {0, 0}};
  SpringJacobian<double> jacobian;
  NodeVectors<double> rhs, push, product;
  jacobian.Assemble(model, state, forces, 0.1, 0.0, 1, &rhs);
  push.x = {0, 1};
  push.y = {0, 1};
  push.z = {0, 0};
  product.Resize(2);
  jacobian.Multiply(push, 0, &product);
  EXPECT_DOUBLE_EQ(product.x[1], 2.0 + 0.01 * 10.0);  // m + h^2 k_c along the spring
  EXPECT_DOUBLE_EQ(product.y[1], 2.0);                // m alone across it
  EXPECT_EQ(product.x[0], 0.0);                       // the pinned row is filtered out

  state.x[1] = 1.5;  // stretched: k along the spring, k (1 - L/|d|) = k / 3 across it
  jacobian.Assemble(model, state, forces, 0.1, 0.0, 1, &rhs);
  jacobian.Multiply(push, 0, &product);
  EXPECT_DOUBLE_EQ(product.x[1], 2.0 + 0.01 * 100.0);
  EXPECT_NEAR(product.y[1], 2.0 + 0.01 * 100.0 / 3, 1e-12);
}

}  // namespace
}  // namespace flagsim::sim
