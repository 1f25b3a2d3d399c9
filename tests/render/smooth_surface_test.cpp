// The smooth surface through the cloth's nodes: it passes through every node exactly, reproduces a
// plane sheet (a linear grid stays linear, edges included), keeps out of the pole where chords
// between hoist nodes would cut into it, and is refined as much as the picture needs and no more.
#include "server/render/smooth_surface.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace flagsim::render {
namespace {

/// cols x rows nodes at position(c, r).
template <class Position>
NodeGrid Grid(int cols, int rows, const Position& position) {
  NodeGrid grid;
  grid.cols = cols;
  grid.rows = rows;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      const Eigen::Vector3f p = position(c, r);
      grid.x.push_back(p.x());
      grid.y.push_back(p.y());
      grid.z.push_back(p.z());
    }
  }
  return grid;
}

Eigen::Vector3f At(const NodeGrid& grid, int c, int r) {
  const size_t i = size_t(r) * grid.cols + c;
  return {grid.x[i], grid.y[i], grid.z[i]};
}

TEST(SmoothSurface, ItPassesThroughEveryNode) {
  const NodeGrid grid = Grid(7, 5, [](int c, int r) {
    return Eigen::Vector3f(0.2f * c, 2 - 0.2f * r, 0.1f * std::sin(1.3f * c + 0.7f * r));
  });
  for (const int factor : {1, 2, 3, 4}) {
    NodeGrid refined;
    RefineGrid(grid, factor, 0.0f, &refined);
    ASSERT_EQ(refined.cols, 6 * factor + 1);
    ASSERT_EQ(refined.rows, 4 * factor + 1);
    for (int r = 0; r < grid.rows; ++r) {
      for (int c = 0; c < grid.cols; ++c) EXPECT_EQ(At(refined, c * factor, r * factor), At(grid, c, r)) << factor;
    }
  }
}

TEST(SmoothSurface, APlaneSheetStaysPlaneAndEvenlySpaced) {
  const NodeGrid grid = Grid(5, 4, [](int c, int r) { return Eigen::Vector3f(0.3f * c + 0.1f * r, 2 - 0.25f * r, 0.05f * c); });
  NodeGrid refined;
  RefineGrid(grid, 4, 0.0f, &refined);
  for (int r = 0; r < refined.rows; ++r) {
    for (int c = 0; c < refined.cols; ++c) {
      const float cc = c / 4.0f, rr = r / 4.0f;  // in node units
      const Eigen::Vector3f expected(0.3f * cc + 0.1f * rr, 2 - 0.25f * rr, 0.05f * cc);
      EXPECT_LT((At(refined, c, r) - expected).norm(), 1e-5f) << c << ", " << r;
    }
  }
}

TEST(SmoothSurface, ItKeepsOutOfThePole) {
  // The hoist wraps half round a pole of radius 0.05 m: chords between its nodes cut inside.
  const float radius = 0.05f;
  const NodeGrid grid = Grid(6, 4, [&](int c, int r) {
    const float angle = c < 3 ? float(M_PI) * (0.5f - c / 4.0f) : 0;
    const Eigen::Vector3f on_pole(radius * std::sin(angle), 2 - 0.2f * r, radius * std::cos(angle));
    return c < 3 ? on_pole : Eigen::Vector3f(0.1f * (c - 2), 2 - 0.2f * r, 0);
  });
  NodeGrid refined;
  RefineGrid(grid, 4, radius, &refined);
  float closest = INFINITY;
  for (size_t i = 0; i < refined.x.size(); ++i) closest = std::min(closest, std::hypot(refined.x[i], refined.z[i]));
  EXPECT_GE(closest, radius * (1 - 1e-6f));
  NodeGrid unclamped;
  RefineGrid(grid, 4, 0.0f, &unclamped);
  float closest_unclamped = INFINITY;
  for (size_t i = 0; i < unclamped.x.size(); ++i)
    closest_unclamped = std::min(closest_unclamped, std::hypot(unclamped.x[i], unclamped.z[i]));
  EXPECT_LT(closest_unclamped, radius * 0.99f) << "the case is one where the surface would cut into the pole";
}

TEST(SmoothSurface, RefinedAsMuchAsThePictureNeeds) {
  const NodeGrid grid = Grid(16, 12, [](int c, int r) { return Eigen::Vector3f(0.1f * c, 2.2f - 0.1f * r, 0); });
  Camera camera;  // 1280 x 720, about 40 degrees
  camera.target = Eigen::Vector3d(0.75, 1.65, 0);
  camera.eye = Eigen::Vector3d(0.75, 1.65, 60);
  EXPECT_EQ(RefinementFor(grid, camera), 1) << "far: a cell is a few pixels";
  camera.eye = Eigen::Vector3d(0.75, 1.65, 1.0);
  EXPECT_EQ(RefinementFor(grid, camera), kMaxRefinement) << "near: a cell is ~100 px";
  camera.eye = Eigen::Vector3d(0.75, 1.65, 6);  // a cell ~16 px: refined twice
  EXPECT_EQ(RefinementFor(grid, camera), 2);
}

}  // namespace
}  // namespace flagsim::render
