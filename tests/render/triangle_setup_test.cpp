#include "server/render/triangle_setup.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

namespace flagsim::render {
namespace {

ScreenVertex At(float x, float y, float z = 0.5f, float inverse_w = 1.0f) {
  ScreenVertex v;
  v.x = x;
  v.y = y;
  v.z = z;
  v.inverse_w = inverse_w;
  return v;
}

/// How many times each pixel of a width x height image is covered by `triangles`.
std::vector<int> Coverage(const std::vector<std::array<ScreenVertex, 3>>& triangles, int width, int height) {
  std::vector<int> count(size_t(width) * height, 0);
  for (const auto& t : triangles) {
    TriangleSetup setup;
    if (!SetupTriangle(t[0], t[1], t[2], width, height, &setup)) continue;
    for (int y = setup.min_y; y <= setup.max_y; ++y) {
      int first = 0, last = 0;
      if (!RowSpan(setup, y, &first, &last)) continue;
      for (int x = first; x <= last; ++x) ++count[size_t(y) * width + x];
    }
  }
  return count;
}

/// A square with corners on pixel centres' grid lines cut into triangles around an inner point.
std::vector<std::array<ScreenVertex, 3>> Fan(float x0, float y0, float x1, float y1, float cx, float cy) {
  const ScreenVertex corners[4] = {At(x0, y0), At(x1, y0), At(x1, y1), At(x0, y1)};
  std::vector<std::array<ScreenVertex, 3>> triangles;
  for (int i = 0; i < 4; ++i) triangles.push_back({At(cx, cy), corners[i], corners[(i + 1) % 4]});
  return triangles;
}

TEST(TriangleSetup, TwoTrianglesCoverASquareExactlyOnce) {
  // Edges through pixel centres: the top-left rule decides every one of them.
  const std::vector<std::array<ScreenVertex, 3>> square = {
      {At(2.5f, 2.5f), At(10.5f, 2.5f), At(10.5f, 10.5f)},
      {At(2.5f, 2.5f), At(10.5f, 10.5f), At(2.5f, 10.5f)}};
  const std::vector<int> count = Coverage(square, 16, 16);
  for (int y = 0; y < 16; ++y) {
    for (int x = 0; x < 16; ++x) {
      // centres (x + 0.5) in [2.5, 10.5): the top and left edges are in, the others out
      const bool inside = x >= 2 && x < 10 && y >= 2 && y < 10;
      EXPECT_EQ(count[y * 16 + x], inside ? 1 : 0) << x << "," << y;
    }
  }
}

TEST(TriangleSetup, AnyTessellationCoversEachPixelOnce) {
  std::mt19937 random(5);
  std::uniform_real_distribution<float> jitter(0.0f, 1.0f);
  for (int trial = 0; trial < 200; ++trial) {
    // a square with sub-pixel corners, fanned from a random inner point, either winding
    const float x0 = 1 + 3 * jitter(random), y0 = 1 + 3 * jitter(random);
    const float x1 = x0 + 4 + 20 * jitter(random), y1 = y0 + 4 + 20 * jitter(random);
    auto triangles = Fan(x0, y0, x1, y1, x0 + (x1 - x0) * (0.2f + 0.6f * jitter(random)),
                         y0 + (y1 - y0) * (0.2f + 0.6f * jitter(random)));
    if (trial % 2) {
      for (auto& t : triangles) std::swap(t[1], t[2]);
    }
    const std::vector<int> count = Coverage(triangles, 32, 32);
    for (int y = 0; y < 32; ++y) {
      for (int x = 0; x < 32; ++x) {
        // the square's own coverage by the same rule: centres in [x0, x1) x [y0, y1), snapped
        const auto snap = [](float v) { return std::lround(double(v) * 256); };
        const long cx = long(x) * 256 + 128, cy = long(y) * 256 + 128;
        const bool inside = cx >= snap(x0) && cx < snap(x1) && cy >= snap(y0) && cy < snap(y1);
        ASSERT_EQ(count[y * 32 + x], inside ? 1 : 0) << "trial " << trial << " pixel " << x << "," << y;
      }
    }
  }
}

TEST(TriangleSetup, DegenerateAndOffscreenTrianglesCoverNothing) {
  TriangleSetup setup;
  EXPECT_FALSE(SetupTriangle(At(1, 1), At(5, 5), At(9, 9), 16, 16, &setup));     // a line
  EXPECT_FALSE(SetupTriangle(At(20, 1), At(30, 1), At(25, 8), 16, 16, &setup));  // right of the image
  EXPECT_FALSE(SetupTriangle(At(3.6f, 3.6f), At(3.9f, 3.6f), At(3.6f, 3.9f), 16, 16, &setup));  // no centre
}

TEST(TriangleSetup, FacingFollowsTheWinding) {
  // Counter-clockwise in a y-up view is front: with y down that is (0,10) (10,10) (0,0) here.
  EXPECT_FALSE(IsBackFacing(At(0, 10), At(10, 10), At(0, 0)));
  EXPECT_TRUE(IsBackFacing(At(0, 10), At(0, 0), At(10, 10)));
  TriangleSetup setup;
  ASSERT_TRUE(SetupTriangle(At(0, 10), At(0, 0), At(10, 10), 16, 16, &setup));
  EXPECT_TRUE(setup.back_facing);
}

TEST(TriangleSetup, PlanesInterpolateLinearValuesExactlyAtPixelCentres) {
  // Channel 0 = 3 + 0.25 x - 0.5 y at each vertex: the plane must give it back at every centre.
  const auto f = [](float x, float y) { return 3 + 0.25f * x - 0.5f * y; };
  ScreenVertex v[3] = {At(1.3f, 2.2f), At(14.7f, 4.1f), At(6.2f, 13.9f)};
  for (ScreenVertex& vertex : v) vertex.channels[0] = f(vertex.x, vertex.y);
  TriangleSetup setup;
  ASSERT_TRUE(SetupTriangle(v[0], v[1], v[2], 16, 16, &setup));
  int checked = 0;
  for (int y = setup.min_y; y <= setup.max_y; ++y) {
    int first = 0, last = 0;
    if (!RowSpan(setup, y, &first, &last)) continue;
    for (int x = first; x <= last; ++x, ++checked) {
      const float fx = float(x - setup.min_x), fy = float(y - setup.min_y);
      const Plane& p = setup.channels[0];
      const float inverse_w = setup.inverse_w.origin + setup.inverse_w.dx * fx + setup.inverse_w.dy * fy;
      const float value = (p.origin + p.dx * fx + p.dy * fy) / inverse_w;
      EXPECT_NEAR(value, f(x + 0.5f, y + 0.5f), 2e-3f);
    }
  }
  EXPECT_GT(checked, 40);
}

TEST(TriangleSetup, PerspectiveCorrectInterpolation) {
  // With w differing per vertex, a channel is interpolated as (sum l_i c_i / w_i) / (sum l_i / w_i),
  // l the screen-space barycentrics: here checked at the centroid of a snapped triangle.
  ScreenVertex v[3] = {At(0, 0, 0.5f, 1.0f), At(12, 0, 0.5f, 0.25f), At(0, 12, 0.5f, 0.5f)};
  v[0].channels[0] = 0;
  v[1].channels[0] = 1;
  v[2].channels[0] = 2;
  TriangleSetup setup;
  ASSERT_TRUE(SetupTriangle(v[0], v[1], v[2], 16, 16, &setup));
  // pixel (3, 3): centre (3.5, 3.5); barycentrics l1 = 3.5 / 12, l2 = 3.5 / 12, l0 = 1 - l1 - l2
  const float l1 = 3.5f / 12, l2 = 3.5f / 12, l0 = 1 - l1 - l2;
  const float expected = (l1 * 1 * 0.25f + l2 * 2 * 0.5f) / (l0 * 1.0f + l1 * 0.25f + l2 * 0.5f);
  const float fx = float(3 - setup.min_x), fy = float(3 - setup.min_y);
  const Plane& p = setup.channels[0];
  const float inverse_w = setup.inverse_w.origin + setup.inverse_w.dx * fx + setup.inverse_w.dy * fy;
  EXPECT_NEAR((p.origin + p.dx * fx + p.dy * fy) / inverse_w, expected, 1e-5f);
}

}  // namespace
}  // namespace flagsim::render

namespace flagsim::render {
namespace {

TEST(RowSpans, SteppingRowByRowGivesTheSameSpansAsSolvingEachRow) {
  std::mt19937 random(11);
  std::uniform_real_distribution<float> coordinate(-20.0f, 120.0f);
  for (int trial = 0; trial < 500; ++trial) {
    TriangleSetup setup;
    if (!SetupTriangle(At(coordinate(random), coordinate(random)), At(coordinate(random), coordinate(random)),
                       At(coordinate(random), coordinate(random)), 100, 100, &setup)) {
      continue;
    }
    RowSpans spans(setup, setup.min_y);
    for (int y = setup.min_y; y <= setup.max_y; ++y, spans.NextRow()) {
      int first = 0, last = 0, step_first = 0, step_last = 0;
      const bool solved = RowSpan(setup, y, &first, &last);
      ASSERT_EQ(spans.Span(&step_first, &step_last), solved) << "trial " << trial << " row " << y;
      if (solved) {
        ASSERT_EQ(step_first, first);
        ASSERT_EQ(step_last, last);
      }
    }
  }
}

TEST(LaneSpans, NarrowTrianglesGetTheSameSpansInAnyWindow) {
  std::mt19937 random(12);
  std::uniform_real_distribution<float> corner(-4.0f, 104.0f), offset(-6.0f, 6.0f);
  int narrow = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const float x = corner(random), y = corner(random);
    TriangleSetup setup;
    if (!SetupTriangle(At(x, y), At(x + offset(random), y + offset(random)),
                       At(x + offset(random), y + offset(random)), 100, 100, &setup) ||
        !setup.narrow) {
      continue;
    }
    ++narrow;
    // Windows from the box's first column and from each column after it, as tiles cut it.
    for (int x0 = setup.min_x; x0 <= setup.max_x; ++x0) {
      const int x_last = std::min(setup.max_x, x0 + LaneSpans::kWidth - 1);
      LaneSpans spans(setup, x0, x_last, setup.min_y);
      for (int y = setup.min_y; y <= setup.max_y; ++y, spans.NextRow()) {
        int first = 0, last = 0, lane_first = 0, lane_last = 0;
        const bool solved = RowSpan(setup, y, &first, &last);
        first = std::max(first, x0);
        last = std::min(last, x_last);
        ASSERT_EQ(spans.Span(&lane_first, &lane_last), solved && first <= last) << "trial " << trial;
        if (solved && first <= last) {
          ASSERT_EQ(lane_first, first);
          ASSERT_EQ(lane_last, last);
        }
      }
    }
  }
  EXPECT_GT(narrow, 1000);
}

TEST(CoverOfBox, NoneAndAllAgreeWithTheRowSpans) {
  std::mt19937 random(13);
  std::uniform_real_distribution<float> coordinate(-20.0f, 120.0f);
  int decided = 0;
  for (int trial = 0; trial < 500; ++trial) {
    TriangleSetup setup;
    if (!SetupTriangle(At(coordinate(random), coordinate(random)), At(coordinate(random), coordinate(random)),
                       At(coordinate(random), coordinate(random)), 100, 100, &setup)) {
      continue;
    }
    std::uniform_int_distribution<int> x(setup.min_x, setup.max_x), y(setup.min_y, setup.max_y);
    for (int box = 0; box < 20; ++box) {
      const int xa = x(random), xb = x(random), ya = y(random), yb = y(random);
      const int x0 = std::min(xa, xb), x1 = std::max(xa, xb), y0 = std::min(ya, yb), y1 = std::max(ya, yb);
      int covered = 0;
      for (int row = y0; row <= y1; ++row) {
        int first = 0, last = 0;
        if (RowSpan(setup, row, &first, &last))
          covered += std::max(0, std::min(last, x1) - std::max(first, x0) + 1);
      }
      const BoxCover cover = CoverOfBox(setup, x0, y0, x1, y1);
      if (cover == BoxCover::kNone) {
        EXPECT_EQ(covered, 0) << "trial " << trial;
      } else if (cover == BoxCover::kAll) {
        EXPECT_EQ(covered, (x1 - x0 + 1) * (y1 - y0 + 1)) << "trial " << trial;
      }
      decided += cover != BoxCover::kPart;
    }
  }
  EXPECT_GT(decided, 1000);
}

TEST(LaneSpans, OnlySmallTrianglesAreNarrow) {
  TriangleSetup setup;
  ASSERT_TRUE(SetupTriangle(At(10, 10), At(18, 10), At(10, 60), 100, 100, &setup));
  EXPECT_TRUE(setup.narrow);
  ASSERT_TRUE(SetupTriangle(At(10, 10), At(18.5f, 10), At(10, 60), 100, 100, &setup));
  EXPECT_FALSE(setup.narrow);
  // Clamped to the image, the box is narrow, but not the triangle.
  ASSERT_TRUE(SetupTriangle(At(-300, 10), At(4, 10), At(4, 14), 100, 100, &setup));
  EXPECT_FALSE(setup.narrow);
}

}  // namespace
}  // namespace flagsim::render
