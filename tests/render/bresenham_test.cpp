#include "server/render/bresenham.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "tests/render/tile_drawing.hpp"

namespace flagsim::render {
namespace {

struct Pixel {
  int x, y;
};

std::vector<Pixel> Line(int x0, int y0, int x1, int y1) {
  std::vector<Pixel> pixels;
  Bresenham(x0, y0, x1, y1, [&](int x, int y, float) { pixels.push_back({x, y}); });
  return pixels;
}

/// The properties that define Bresenham's line, checked for one segment.
void ExpectBresenham(int x0, int y0, int x1, int y1) {
  SCOPED_TRACE(::testing::Message() << "(" << x0 << "," << y0 << ") -> (" << x1 << "," << y1 << ")");
  const std::vector<Pixel> pixels = Line(x0, y0, x1, y1);
  const int dx = x1 - x0, dy = y1 - y0;
  const bool x_major = std::abs(dx) >= std::abs(dy);
  ASSERT_EQ(pixels.size(), size_t(std::max(std::abs(dx), std::abs(dy)) + 1));
  EXPECT_EQ(pixels.front().x, x0);
  EXPECT_EQ(pixels.front().y, y0);
  EXPECT_EQ(pixels.back().x, x1);
  EXPECT_EQ(pixels.back().y, y1);
  for (size_t i = 1; i < pixels.size(); ++i) {
    const int step_x = pixels[i].x - pixels[i - 1].x, step_y = pixels[i].y - pixels[i - 1].y;
    // one step along the major axis each time, at most one along the minor axis
    EXPECT_EQ(std::abs(x_major ? step_x : step_y), 1);
    EXPECT_LE(std::abs(x_major ? step_y : step_x), 1);
  }
  for (const Pixel& p : pixels) {
    // each pixel is the nearest to the ideal line along the minor axis (within half a pixel)
    const double offset =
        x_major ? (p.y - y0) - double(dy) * (p.x - x0) / dx : (p.x - x0) - double(dx) * (p.y - y0) / dy;
    EXPECT_LE(std::abs(offset), 0.5 + 1e-9);
  }
}

TEST(Bresenham, AllEightOctants) {
  // From the origin to points in each octant, steep and shallow, both directions.
  for (const auto& [dx, dy] : std::vector<std::pair<int, int>>{
           {7, 3}, {3, 7}, {-3, 7}, {-7, 3}, {-7, -3}, {-3, -7}, {3, -7}, {7, -3}, {13, 5}, {-5, -13}}) {
    ExpectBresenham(0, 0, dx, dy);
    ExpectBresenham(10, -4, 10 + dx, -4 + dy);
  }
}

TEST(Bresenham, AxisAlignedDiagonalAndDegenerate) {
  ExpectBresenham(0, 0, 9, 0);
  ExpectBresenham(0, 0, 0, -9);
  ExpectBresenham(0, 0, 6, 6);
  ExpectBresenham(0, 0, -6, 6);
  const std::vector<Pixel> point = Line(4, 5, 4, 5);
  ASSERT_EQ(point.size(), 1u);
  EXPECT_EQ(point[0].x, 4);
  EXPECT_EQ(point[0].y, 5);
}

TEST(Bresenham, DepthRunsFromEndToEnd) {
  std::vector<float> ts;
  Bresenham(0, 0, 4, 1, [&](int, int, float t) { ts.push_back(t); });
  EXPECT_EQ(ts, (std::vector<float>{0.0f, 0.25f, 0.5f, 0.75f, 1.0f}));
}

TEST(DrawLine, TileByTileDrawsWhatTheWholeLineDraws) {
  Framebuffer whole, tiled;
  whole.Resize(40, 30);
  tiled.Resize(40, 30);
  LineSetup line;
  line.x0 = 2;
  line.y0 = 27;
  line.x1 = 37;
  line.y1 = 3;
  line.z0 = 0.2f;
  line.z1 = 0.6f;
  line.rgb[0] = 255;
  DrawInTile(&whole, TileRect{0, 0, 40, 30}, [&](const TileTarget& tile) { DrawLine(line, tile); });
  for (int y = 0; y < 30; y += 8) {
    for (int x = 0; x < 40; x += 8) {
      DrawInTile(&tiled, TileRect{x, y, std::min(x + 8, 40), std::min(y + 8, 30)},
                 [&](const TileTarget& tile) { DrawLine(line, tile); });
    }
  }
  EXPECT_EQ(whole.rgb, tiled.rgb);
  EXPECT_EQ(whole.depth, tiled.depth);
}

TEST(DrawLine, HiddenBehindNearerDepth) {
  Framebuffer framebuffer;
  framebuffer.Resize(10, 10);
  std::fill(framebuffer.depth.begin(), framebuffer.depth.end(), 0.5f);
  LineSetup far_line;
  far_line.x1 = 9;
  far_line.z0 = far_line.z1 = 0.7f;
  far_line.rgb[1] = 200;
  DrawInTile(&framebuffer, TileRect{0, 0, 10, 10}, [&](const TileTarget& tile) { DrawLine(far_line, tile); });
  EXPECT_EQ(framebuffer.Pixel(5, 0)[1], 0);
  LineSetup near_line = far_line;
  near_line.z0 = near_line.z1 = 0.3f;
  DrawInTile(&framebuffer, TileRect{0, 0, 10, 10},
             [&](const TileTarget& tile) { DrawLine(near_line, tile); });
  EXPECT_EQ(framebuffer.Pixel(5, 0)[1], 200);
}

}  // namespace
}  // namespace flagsim::render
