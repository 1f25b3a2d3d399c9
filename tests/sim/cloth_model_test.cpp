#include "server/sim/cloth_model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "lab/stability.hpp"

namespace flagsim::sim {
namespace {

TEST(ClothModel, MassesAddUpToTheFlag) {
  SimParams params;
  params.mass = 0.4;
  const ClothModel<double> model = BuildClothModel<double>(params);
  EXPECT_EQ(model.num_nodes(), params.cols * params.rows);
  const double total = std::accumulate(model.mass.begin(), model.mass.end(), 0.0);
  EXPECT_NEAR(total, 0.4, 1e-12);
}

TEST(ClothModel, HoistEdgeIsPinnedAndNothingElse) {
  const ClothModel<float> model = BuildClothModel<float>(SimParams{});
  for (int r = 0; r < model.rows; ++r) {
    for (int c = 0; c < model.cols; ++c) EXPECT_EQ(model.pinned(model.index(r, c)), c == 0);
  }
}

TEST(ClothModel, RestGridSpansTheFlagBelowThePoleTop) {
  SimParams params;
  const ClothModel<double> model = BuildClothModel<double>(params);
  const int last = model.num_nodes() - 1;
  EXPECT_DOUBLE_EQ(model.rest_x[last] - model.rest_x[0], params.width);
  EXPECT_NEAR(model.rest_y[0] - model.rest_y[last], params.height, 1e-12);
  EXPECT_LT(model.rest_y[0], params.pole_height);
}

TEST(ClothModel, SpringConstantsFollowTheSheetModulus) {
  // k = modulus dx dy / L^2: a square grid gives the structural springs exactly the modulus.
  SimParams params;
  params.cols = 11;
  params.rows = 11;
  params.width = 1.0;
  params.height = 1.0;
  const ClothModel<double> model = BuildClothModel<double>(params);
  for (const SpringFamily<double>& family : model.families) {
    const double expected = family.kind == SpringKind::kStructural ? params.forces.stiffness
                                                                   : params.forces.shear_stiffness / 2;
    EXPECT_NEAR(family.stiffness, expected, 1e-9 * expected);
  }
}

TEST(ClothModel, CompressedSpringsAreSofter) {
  // Choi and Ko 2002's split: structural and shear springs resist compression with compression
  // times their stiffness.
  SimParams params;
  params.compression = 0.25;
  ClothModel<double> model = BuildClothModel<double>(params);
  for (const SpringFamily<double>& family : model.families) {
    EXPECT_DOUBLE_EQ(family.compression_stiffness, 0.25 * family.stiffness);
  }
  params.compression = 1;  // as stiff in compression as in stretch: the same constant, bit for bit
  SetMaterialConstants(params, &model);
  for (const SpringFamily<double>& family : model.families) {
    EXPECT_EQ(family.compression_stiffness, family.stiffness);
  }
}

TEST(ClothModel, RefiningTheGridKeepsTheSheetAsStiff) {
  // A row of n structural springs of constant k in series stretches like one of k / n; with
  // k proportional to 1 / L^2 times the cell area, the whole sheet's stiffness stays put.
  SimParams coarse, fine;
  fine.cols = 2 * coarse.cols - 1;
  fine.rows = 2 * coarse.rows - 1;
  const auto series = [](const SimParams& params) {
    const ClothModel<double> model = BuildClothModel<double>(params);
    // along one row: (cols - 1) springs in series; rows of them in parallel
    return model.families[0].stiffness / (params.cols - 1) * (params.rows - 1);
  };
  EXPECT_NEAR(series(fine), series(coarse), 1e-9 * series(coarse));
}

TEST(ClothModel, FrequencyBoundHoldsForTheLowestOrderCase) {
  // 2 x 2 grid, structural springs only, column 0 pinned: along x each free node is on its own
  // horizontal spring (w^2 = k_h / m); along y the two free nodes share the vertical spring
  // (w^2 = 2 k_v / m). Gershgorin's 2 (k_h + k_v) / m is looser; the estimate must lie between.
  SimParams params;
  params.cols = 2;
  params.rows = 2;
  params.forces.shear_stiffness = 0;
  params.forces.bending_stiffness = 0;
  const ClothModel<double> model = BuildClothModel<double>(params);
  const FrequencyBound bound = EstimateFrequencyBound(model, 0.0);
  const double k_h = model.families[0].stiffness, k_v = model.families[1].stiffness;
  const double exact = std::max(k_h, 2 * k_v) * model.inverse_mass[1];
  EXPECT_GE(bound.omega_squared, exact);
  EXPECT_LE(bound.omega_squared, 2 * (k_h + k_v) * model.inverse_mass[1]);
}

// Against dense eigensolves: never below the highest frequency and damping rate, never far above.
TEST(ClothModel, FrequencyBoundIsAnUpperBoundAndTight) {
  for (const int cols : {3, 8, 16, 20}) {
    for (const double shear : {0.0, 0.1, 1.0}) {
      SimParams params;
      params.cols = cols;
      params.rows = std::max(2, cols * 3 / 4);
      params.forces.shear_stiffness = shear * params.forces.stiffness;
      const double omega_squared = lab::TopEigenvalue(params, false);
      const double damping_rate = lab::TopEigenvalue(params, true);
      const FrequencyBound bound = EstimateFrequencyBound(BuildClothModel<double>(params), 0.0);
      EXPECT_GE(bound.omega_squared, omega_squared) << cols << " cols, shear " << shear;
      EXPECT_LE(bound.omega_squared, 1.3 * omega_squared) << cols << " cols, shear " << shear;
      EXPECT_GE(bound.damping_rate, damping_rate) << cols << " cols, shear " << shear;
      EXPECT_LE(bound.damping_rate, 1.3 * damping_rate) << cols << " cols, shear " << shear;
    }
  }
}

}  // namespace
}  // namespace flagsim::sim
