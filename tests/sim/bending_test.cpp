#include "server/sim/bending.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "lab/shape_statistics.hpp"
#include "server/sim/forces.hpp"
#include "server/sim/simulation.hpp"
#include "tests/sim/sim_test_util.hpp"

namespace flagsim::sim {
namespace {

using testing::Isolated;
using testing::NoWind;
using testing::Unpin;

/// The rest grid (no imperfection) of `cols` x `rows` nodes over the default 1.5 m x 1 m flag.
ClothModel<double> FlatSheet(int cols, int rows, double bending = 1e-3) {
  SimParams params;
  params.cols = cols;
  params.rows = rows;
  params.imperfection = 0;
  params.forces.bending_stiffness = bending;
  return BuildClothModel<double>(params);
}

/// The rest grid rolled isometrically onto a cylinder of radius R whose axis lies in the sheet's
/// plane at `angle` (rad) to the rows: a bend of curvature 1 / R across that axis.
ClothState<double> Rolled(const ClothModel<double>& model, double R, double angle) {
  ClothState<double> state = RestState(model);
  const double ax = std::cos(angle), ay = std::sin(angle);  // the axis, in the sheet's plane
  for (int i = 0; i < model.num_nodes(); ++i) {
    const double u = -ay * model.rest_x[i] + ax * model.rest_y[i];  // arc length across the axis
    const double w = ax * model.rest_x[i] + ay * model.rest_y[i];   // along the axis
    const double across = R * std::sin(u / R);
    state.x[i] = w * ax - across * ay;
    state.y[i] = w * ay + across * ax;
    state.z[i] = R * (1 - std::cos(u / R));
  }
  return state;
}

TEST(Bending, ACylinderStoresHalfBOverRSquaredPerSquareMetreInEveryDirection) {
  // (B / 2) integral of (k1 + k2)^2 dA with k1 = 1 / R, k2 = 0. The sum leaves out a strip of
  // half a cell along the edges (the boundary nodes' areas), so at a finite grid the energy is
  // the interior's share; that share -> 1 as the grid refines.
  const double B = 1e-3, R = 0.4;
  for (const auto& [cols, rows] : {std::pair{32, 24}, std::pair{64, 48}, std::pair{128, 96}}) {
    const ClothModel<double> model = FlatSheet(cols, rows, B);
    const double interior = (cols - 2) * model.dx * (rows - 2) * model.dy;
    const double expected = B / (2 * R * R) * interior;
    for (const double angle : {0.0, 0.5, M_PI / 4, M_PI / 2, 2.0}) {
      const ClothState<double> rolled = Rolled(model, R, angle);
      EXPECT_NEAR(BendingEnergy(model, rolled.x, rolled.y, rolled.z), expected, 0.02 * expected)
          << cols << " x " << rows << " at " << angle << " rad";
    }
  }
}

TEST(Bending, AnAffineMapOfTheFlatSheetHasNoEnergyAndNoForce) {
  ClothModel<double> model = FlatSheet(9, 7);
  ClothState<double> moved = RestState(model);
  for (int i = 0; i < model.num_nodes(); ++i) {  // rotated, sheared, stretched, moved
    const double x = model.rest_x[i], y = model.rest_y[i];
    moved.x[i] = 0.8 * x - 0.3 * y + 1.0;
    moved.y[i] = 0.5 * x + 1.1 * y - 2.0;
    moved.z[i] = 0.6 * x + 0.2 * y + 0.5;
  }
  EXPECT_NEAR(BendingEnergy(model, moved.x, moved.y, moved.z), 0.0, 1e-20);
  Unpin(&model);
  ForceEvaluator<double> evaluator;
  NodeForces<double> forces;
  evaluator.Evaluate(model, Isolated(), WindField(NoWind()), moved, 0, &forces,
                     ForceTerms::kBending);
  for (int i = 0; i < model.num_nodes(); ++i) {
    EXPECT_NEAR(forces.x[i], 0.0, 1e-12);
    EXPECT_NEAR(forces.y[i], 0.0, 1e-12);
    EXPECT_NEAR(forces.z[i], 0.0, 1e-12);
  }
}

/// A sheet in a smooth, non-isometric pose, at rest.
ClothState<double> Rumpled(const ClothModel<double>& model) {
  ClothState<double> state = RestState(model);
  for (int i = 0; i < model.num_nodes(); ++i) {
    state.z[i] = 0.03 * std::sin(3.1 * model.rest_x[i]) * std::cos(2.3 * model.rest_y[i]) + 0.01 * std::sin(0.7 * i);
    state.x[i] += 0.004 * std::cos(1.3 * i);
  }
  return state;
}

TEST(Bending, TheForceIsMinusTheEnergysGradient) {
  ClothModel<double> model = FlatSheet(8, 6);
  Unpin(&model);
  ClothState<double> state = Rumpled(model);
  ForceEvaluator<double> evaluator;
  NodeForces<double> forces;
  evaluator.Evaluate(model, Isolated(), WindField(NoWind()), state, 0, &forces, ForceTerms::kBending);
  const double step = 1e-6;
  for (int i = 0; i < model.num_nodes(); ++i) {
    for (std::vector<double>* coordinate : {&state.x, &state.y, &state.z}) {
      const double kept = (*coordinate)[i];
      (*coordinate)[i] = kept + step;
      const double up = BendingEnergy(model, state.x, state.y, state.z);
      (*coordinate)[i] = kept - step;
      const double down = BendingEnergy(model, state.x, state.y, state.z);
      (*coordinate)[i] = kept;
      const double force = coordinate == &state.x ? forces.x[i] : coordinate == &state.y ? forces.y[i] : forces.z[i];
      EXPECT_NEAR(force, -(up - down) / (2 * step), 1e-7) << "node " << i;
    }
  }
}

TEST(Bending, ItsDampingIsBetaTimesTheStiffnessOnTheVelocities) {
  // f = -B Q (x + beta v): velocities shaped like a pose pull like that pose times beta.
  ClothModel<double> model = FlatSheet(8, 6);
  model.bending_damping = 0.01;
  Unpin(&model);
  const ClothState<double> pose = Rumpled(model);
  ClothState<double> moving = RestState(model);
  moving.vx = pose.x;
  moving.vy = pose.y;
  moving.vz = pose.z;
  ForceEvaluator<double> evaluator;
  NodeForces<double> from_pose, from_velocity;
  evaluator.Evaluate(model, Isolated(), WindField(NoWind()), pose, 0, &from_pose, ForceTerms::kBending);
  evaluator.Evaluate(model, Isolated(), WindField(NoWind()), moving, 0, &from_velocity, ForceTerms::kBending);
  for (int i = 0; i < model.num_nodes(); ++i) {
    EXPECT_NEAR(from_velocity.z[i], 0.01 * from_pose.z[i], 1e-12 + 1e-9 * std::abs(from_pose.z[i]));
  }
}

TEST(Bending, TheRowProductAndDiagonalAreTheForcesMatrix) {
  // B Q p, node by node, is minus the bending force of positions p; its diagonal is e_i . B Q e_i.
  ClothModel<double> model = FlatSheet(9, 7);
  Unpin(&model);
  const ClothState<double> state = Rumpled(model);
  ForceEvaluator<double> evaluator;
  NodeForces<double> forces;
  evaluator.Evaluate(model, Isolated(), WindField(NoWind()), state, 0, &forces, ForceTerms::kBending);
  std::vector<double> unit(model.num_nodes(), 0.0);
  for (int r = 0; r < model.rows; ++r) {
    for (int c = 0; c < model.cols; ++c) {
      const int i = model.index(r, c);
      EXPECT_NEAR(BendingProductAt(model, state.z.data(), r, c), -forces.z[i], 1e-12);
      unit[i] = 1;
      EXPECT_NEAR(BendingDiagonal(model, r, c), BendingProductAt(model, unit.data(), r, c), 1e-9);
      unit[i] = 0;
    }
  }
}

/// The breeze's mean curvature (1/m) over seconds 1 to 3 at a grid, sampled every 20 ms.
double BreezeCurvature(int cols, int rows) {
  SimParams params;
  params.cols = cols;
  params.rows = rows;
  Simulation<float> simulation(params, WindSettings{{6.0, 0.0, 1.5}, 0.2, 0});
  double sum = 0;
  int samples = 0;
  for (int step = 1; step <= 1500; ++step) {
    simulation.Step();
    if (step > 500 && step % 10 == 0) {
      sum += lab::SampleShape(simulation.model(), simulation.state()).curvature;
      ++samples;
    }
  }
  return sum / samples;
}

TEST(Bending, TheBreezesCurvatureDoesNotGrowAsTheGridRefines) {
  // Folds set by the grid grow sharper as it refines (the bend springs this model replaced:
  // 8.2, 14.1 and 23.4 per metre at 32 x 24, 64 x 48 and 128 x 96); the cloth's own stay put.
  const double coarse = BreezeCurvature(24, 16), fine = BreezeCurvature(48, 32);
  EXPECT_GT(coarse, 1.0);  // the flag does fold
  EXPECT_LT(fine, 1.2 * coarse) << coarse << " per metre at 24 x 16, " << fine << " at 48 x 32";
  EXPECT_GT(fine, 0.8 * coarse) << coarse << " per metre at 24 x 16, " << fine << " at 48 x 32";
}

}  // namespace
}  // namespace flagsim::sim
