#include "server/sim/resample.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "server/sim/bending.hpp"
#include "server/sim/simulation.hpp"

namespace flagsim::sim {
namespace {

ClothModel<double> Grid(int cols, int rows) {
  SimParams params;
  params.cols = cols;
  params.rows = rows;
  return BuildClothModel<double>(params);
}

/// A smooth pose and motion of `model`'s free nodes, from their rest positions.
ClothState<double> Posed(const ClothModel<double>& model) {
  ClothState<double> state = RestState(model);
  for (int i = 0; i < model.num_nodes(); ++i) {
    if (model.pinned(i)) continue;
    const double u = model.rest_x[i], v = model.rest_y[i];
    state.z[i] = 0.1 * std::sin(2.0 * u) * std::cos(1.5 * v);
    state.x[i] -= 0.02 * u * u;
    state.vx[i] = 0.3 * v;
    state.vz[i] = -0.5 * u * v;
  }
  state.time = 1.25;
  state.step = 625;
  return state;
}

TEST(Resample, OntoItsOwnGridIsTheIdentityBitForBit) {
  const ClothModel<double> model = Grid(9, 7);
  const ClothState<double> state = Posed(model);
  const ClothState<double> same = Resample(model, state, model);
  EXPECT_EQ(same.x, state.x);
  EXPECT_EQ(same.vz, state.vz);
  EXPECT_EQ(same.time, state.time);
  EXPECT_EQ(same.step, state.step);
}

TEST(Resample, RefinedByHalvingAndBackIsTheIdentityBitForBit) {
  // 9 x 7 and 17 x 13 share every node of the coarser grid.
  const ClothModel<double> coarse = Grid(9, 7), fine = Grid(17, 13);
  const ClothState<double> state = Posed(coarse);
  const ClothState<double> back = Resample(fine, Resample(coarse, state, fine), coarse);
  EXPECT_EQ(back.x, state.x);
  EXPECT_EQ(back.y, state.y);
  EXPECT_EQ(back.z, state.z);
  EXPECT_EQ(back.vx, state.vx);
}

TEST(Resample, AnAffineMotionIsCarriedExactlyToAnyGrid) {
  // Bilinear interpolation reproduces affine functions of (u, v): a flag moved as a whole, sheared
  // and swinging at a uniform rate lands on the new grid as it was.
  const ClothModel<double> from = Grid(11, 8), to = Grid(20, 15);
  ClothState<double> state = RestState(from);
  const auto affine = [](double x, double y) { return 0.3 * x - 0.2 * y + 0.1; };
  for (int i = 0; i < from.num_nodes(); ++i) {
    state.z[i] = affine(from.rest_x[i], from.rest_y[i]);
    state.vy[i] = 2 * affine(from.rest_x[i], from.rest_y[i]);
  }
  const ClothState<double> moved = Resample(from, state, to);
  for (int i = 0; i < to.num_nodes(); ++i) {
    if (to.pinned(i)) continue;
    EXPECT_NEAR(moved.z[i], affine(to.rest_x[i], to.rest_y[i]), 1e-12);
    EXPECT_NEAR(moved.vy[i], 2 * affine(to.rest_x[i], to.rest_y[i]), 1e-12);
  }
}

TEST(Resample, TheHoistStaysOnThePole) {
  const ClothModel<double> from = Grid(9, 7), to = Grid(13, 10);
  const ClothState<double> moved = Resample(from, Posed(from), to);
  for (int r = 0; r < to.rows; ++r) {
    const int i = to.index(r, 0);
    EXPECT_EQ(moved.x[i], to.rest_x[i]);
    EXPECT_EQ(moved.y[i], to.rest_y[i]);
    EXPECT_EQ(moved.vx[i], 0.0);
  }
}

/// The breeze flown for `seconds` at cols x rows.
Simulation<float> Flown(int cols, int rows, double seconds) {
  SimParams params;
  params.cols = cols;
  params.rows = rows;
  Simulation<float> simulation(params, WindSettings{{6.0, 0.0, 1.5}, 0.2, 0});
  for (int i = 0; i < int(std::lround(seconds / params.dt)); ++i) simulation.Step();
  return simulation;
}

TEST(Regrid, RefiningAndComingBackKeepsTheStateBitForBit) {
  // 32 x 24 and 63 x 47 share the coarser grid's nodes: refined and coarsened at once, the flag
  // is where it was, moving as it was.
  Simulation<float> simulation = Flown(32, 24, 1.0);
  const ClothState<float> before = simulation.state();
  simulation.Regrid(63, 47);
  EXPECT_EQ(simulation.model().cols, 63);
  EXPECT_EQ(simulation.params().rows, 47);
  simulation.Regrid(32, 24);
  EXPECT_EQ(simulation.state().x, before.x);
  EXPECT_EQ(simulation.state().vz, before.vz);
  EXPECT_EQ(simulation.state().time, before.time);
  EXPECT_EQ(simulation.state().step, before.step);
}

TEST(Regrid, AnyOtherGridKeepsTheFlagWithinTheResamplingTolerance) {
  // Through 48 x 36 and back, bilinear each way: a node moves by at most the sagitta of a cell,
  // h^2 k / 8, each way, k the cloth's curvature (largest |L x| over the interior nodes, the fly
  // edge's folds not counted: they are measured one node in) and h the coarser grid's spacing.
  Simulation<float> simulation = Flown(32, 24, 1.0);
  const ClothState<float> before = simulation.state();
  const ClothModel<float>& model = simulation.model();
  double curvature = 0;
  for (int r = 1; r + 1 < model.rows; ++r) {
    for (int c = 1; c + 1 < model.cols; ++c) {
      const std::array<double, 3> k = CurvatureAt(model, before.x, before.y, before.z, r, c);
      curvature = std::max(curvature, std::sqrt(k[0] * k[0] + k[1] * k[1] + k[2] * k[2]));
    }
  }
  const double h = std::max(model.dx, model.dy), tolerance = 2 * h * h * curvature / 8;
  simulation.Regrid(48, 36);
  simulation.Regrid(32, 24);
  double largest = 0;
  for (int i = 0; i < before.num_nodes(); ++i) {
    largest = std::max(largest, std::hypot(double(simulation.state().x[i]) - before.x[i],
                                           double(simulation.state().y[i]) - before.y[i],
                                           double(simulation.state().z[i]) - before.z[i]));
  }
  EXPECT_LT(largest, tolerance) << "curvature up to " << curvature << " per metre";
  EXPECT_GT(largest, 0.0);  // not nested: something was interpolated
}

TEST(Regrid, ASwitchMidFlightReplaysBitForBitAndGoesOnFlying) {
  const auto run = [] {
    Simulation<float> simulation = Flown(32, 24, 0.5);
    simulation.Regrid(48, 36);
    for (int i = 0; i < 250; ++i) simulation.Step();
    return simulation;
  };
  const Simulation<float> a = run(), b = run();
  EXPECT_EQ(a.Hash(), b.Hash());
  EXPECT_EQ(a.recoveries(), 0);
  // A snapshot after the switch resumes on the new grid as the original goes on.
  Simulation<float> original = run();
  Simulation<float> resumed(original.Snapshot());
  for (int i = 0; i < 50; ++i) {
    original.Step();
    resumed.Step();
  }
  EXPECT_EQ(resumed.Hash(), original.Hash());
}

}  // namespace
}  // namespace flagsim::sim
