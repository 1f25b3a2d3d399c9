#include "server/sim/rest_imperfection.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "server/sim/cloth_model.hpp"

namespace flagsim::sim {
namespace {

TEST(RestImperfection, ItsLargestDepartureIsTheParameterAndOnlyFreeNodesMove) {
  SimParams params;
  params.imperfection = 2e-3;
  const ClothModel<double> model = BuildClothModel<double>(params);
  double largest = 0;
  for (int i = 0; i < model.num_nodes(); ++i) {
    if (model.pinned(i)) {
      EXPECT_EQ(model.rest_z[i], 0.0) << "node " << i;
    }
    largest = std::max(largest, std::abs(model.rest_z[i]));
  }
  EXPECT_NEAR(largest, 2e-3, 1e-15);
}

TEST(RestImperfection, NoneLeavesTheSheetFlat) {
  SimParams params;
  params.imperfection = 0;
  const ClothModel<float> model = BuildClothModel<float>(params);
  for (const float z : model.rest_z) EXPECT_EQ(z, 0.0f);
}

TEST(RestImperfection, MovesOnlyOutOfThePlaneAndKeepsTheFlatGridsRestLengths) {
  SimParams flat_params, params;
  flat_params.imperfection = 0;
  const ClothModel<double> flat = BuildClothModel<double>(flat_params),
                           model = BuildClothModel<double>(params);
  EXPECT_EQ(model.rest_x, flat.rest_x);
  EXPECT_EQ(model.rest_y, flat.rest_y);
  for (size_t f = 0; f < model.families.size(); ++f) {
    EXPECT_EQ(model.families[f].rest_length, flat.families[f].rest_length);
  }
}

TEST(RestImperfection, IsSmooth) {
  // Low-order shapes: neighbours along a row or down a column differ by a small part of the
  // amplitude, so the springs start stretched by (dz / L)^2 / 2 at most, well under 0.1 %.
  SimParams params;
  const ClothModel<double> model = BuildClothModel<double>(params);
  double steepest = 0;
  for (int r = 0; r < model.rows; ++r) {
    for (int c = 0; c < model.cols; ++c) {
      const double z = model.rest_z[model.index(r, c)];
      if (c + 1 < model.cols)
        steepest = std::max(steepest, std::abs(model.rest_z[model.index(r, c + 1)] - z));
      if (r + 1 < model.rows)
        steepest = std::max(steepest, std::abs(model.rest_z[model.index(r + 1, c)] - z));
    }
  }
  EXPECT_GT(steepest, 0.0);
  EXPECT_LT(steepest, 0.25 * params.imperfection);
  EXPECT_LT(0.5 * std::pow(steepest / double(model.dx), 2), 1e-3);
}

TEST(RestImperfection, IsTheSameOnEveryBuildAndInFloatAsInDouble) {
  SimParams params;
  const ClothModel<double> a = BuildClothModel<double>(params), b = BuildClothModel<double>(params);
  EXPECT_EQ(a.rest_z, b.rest_z);
  const ClothModel<float> single = BuildClothModel<float>(params);
  for (int i = 0; i < a.num_nodes(); ++i) EXPECT_EQ(single.rest_z[i], float(a.rest_z[i])) << "node " << i;
}

}  // namespace
}  // namespace flagsim::sim
