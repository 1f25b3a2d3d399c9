#include "server/model/resample.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace flagsim::model {
namespace {

sim::ClothModel<double> Grid(int cols, int rows) {
  sim::SimParams params;
  params.cols = cols;
  params.rows = rows;
  return sim::BuildClothModel<double>(params);
}

/// A smooth pose and motion of `model`'s free nodes, from their rest positions.
sim::ClothState<double> Posed(const sim::ClothModel<double>& model) {
  sim::ClothState<double> state = sim::RestState(model);
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
  const sim::ClothModel<double> model = Grid(9, 7);
  const sim::ClothState<double> state = Posed(model);
  const sim::ClothState<double> same = Resample(model, state, model);
  EXPECT_EQ(same.x, state.x);
  EXPECT_EQ(same.vz, state.vz);
  EXPECT_EQ(same.time, state.time);
  EXPECT_EQ(same.step, state.step);
}

TEST(Resample, RefinedByHalvingAndBackIsTheIdentityBitForBit) {
  // 9 x 7 and 17 x 13 share every node of the coarser grid.
  const sim::ClothModel<double> coarse = Grid(9, 7), fine = Grid(17, 13);
  const sim::ClothState<double> state = Posed(coarse);
  const sim::ClothState<double> back = Resample(fine, Resample(coarse, state, fine), coarse);
  EXPECT_EQ(back.x, state.x);
  EXPECT_EQ(back.y, state.y);
  EXPECT_EQ(back.z, state.z);
  EXPECT_EQ(back.vx, state.vx);
}

TEST(Resample, AnAffineMotionIsCarriedExactlyToAnyGrid) {
  // Bilinear interpolation reproduces affine functions of (u, v): a flag moved as a whole, sheared
  // and swinging at a uniform rate lands on the new grid as it was.
  const sim::ClothModel<double> from = Grid(11, 8), to = Grid(20, 15);
  sim::ClothState<double> state = sim::RestState(from);
  const auto affine = [](double x, double y) { return 0.3 * x - 0.2 * y + 0.1; };
  for (int i = 0; i < from.num_nodes(); ++i) {
    state.z[i] = affine(from.rest_x[i], from.rest_y[i]);
    state.vy[i] = 2 * affine(from.rest_x[i], from.rest_y[i]);
  }
  const sim::ClothState<double> moved = Resample(from, state, to);
  for (int i = 0; i < to.num_nodes(); ++i) {
    if (to.pinned(i)) continue;
    EXPECT_NEAR(moved.z[i], affine(to.rest_x[i], to.rest_y[i]), 1e-12);
    EXPECT_NEAR(moved.vy[i], 2 * affine(to.rest_x[i], to.rest_y[i]), 1e-12);
  }
}

TEST(Resample, TheHoistStaysOnThePole) {
  const sim::ClothModel<double> from = Grid(9, 7), to = Grid(13, 10);
  const sim::ClothState<double> moved = Resample(from, Posed(from), to);
  for (int r = 0; r < to.rows; ++r) {
    const int i = to.index(r, 0);
    EXPECT_EQ(moved.x[i], to.rest_x[i]);
    EXPECT_EQ(moved.y[i], to.rest_y[i]);
    EXPECT_EQ(moved.vx[i], 0.0);
  }
}

}  // namespace
}  // namespace flagsim::model
