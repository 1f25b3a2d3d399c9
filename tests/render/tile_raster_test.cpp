#include "render/tile_raster.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "tile_drawing.hpp"

namespace flagsim::render {
namespace {

/// A scene of one plain white material, so that colour = D + S.
RenderScene White() {
  RenderScene scene;
  Material white;
  white.colour = Eigen::Vector3f(1, 1, 1);
  scene.materials = {white};
  return scene;
}

ScreenVertex At(float x, float y, float z, float diffuse) {
  ScreenVertex v;
  v.x = x;
  v.y = y;
  v.z = z;
  v.inverse_w = 1;
  v.channels[0] = v.channels[1] = v.channels[2] = diffuse;
  return v;
}

TEST(TileRaster, GouraudColoursAreTheInterpolatedLight) {
  // D = x / 32 at every vertex (S = 0): each pixel shows round(255 (x + 0.5) / 32).
  const RenderScene scene = White();
  Framebuffer framebuffer;
  framebuffer.Resize(32, 32);
  TriangleSetup t;
  ASSERT_TRUE(SetupTriangle(At(0, 0, 0.5f, 0), At(32, 0, 0.5f, 1), At(0, 32, 0.5f, 0), 32, 32, &t));
  ShadeContext context;
  context.scene = &scene;
  DrawInTile(&framebuffer, TileRect{0, 0, 32, 32},
             [&](const TileTarget& tile) { RasterizeTriangle(t, context, tile); });
  for (const auto& [x, y] : {std::pair{0, 0}, std::pair{10, 3}, std::pair{20, 5}, std::pair{5, 20}}) {
    const int expected = int(255 * (x + 0.5f) / 32 + 0.5f);
    EXPECT_NEAR(framebuffer.Pixel(x, y)[0], expected, 1) << x << "," << y;
  }
  EXPECT_EQ(framebuffer.Pixel(31, 31)[0], 0);  // outside: untouched
}

TEST(TileRaster, TheNearerTriangleWinsInEitherOrder) {
  const RenderScene scene = White();
  ShadeContext context;
  context.scene = &scene;
  TriangleSetup near_dark, far_light;
  ASSERT_TRUE(
      SetupTriangle(At(0, 0, 0.3f, 0.2f), At(16, 0, 0.3f, 0.2f), At(0, 16, 0.3f, 0.2f), 16, 16, &near_dark));
  ASSERT_TRUE(
      SetupTriangle(At(0, 0, 0.7f, 0.9f), At(16, 0, 0.7f, 0.9f), At(0, 16, 0.7f, 0.9f), 16, 16, &far_light));
  for (const bool near_first : {true, false}) {
    Framebuffer framebuffer;
    framebuffer.Resize(16, 16);
    DrawInTile(&framebuffer, TileRect{0, 0, 16, 16}, [&](const TileTarget& tile) {
      RasterizeTriangle(near_first ? near_dark : far_light, context, tile);
      RasterizeTriangle(near_first ? far_light : near_dark, context, tile);
    });
    EXPECT_EQ(framebuffer.Pixel(3, 3)[0], 51) << near_first;  // 0.2 * 255
    EXPECT_FLOAT_EQ(framebuffer.depth[3 * 16 + 3], 0.3f);
  }
}

TEST(TileRaster, OnlyTheTileIsTouched) {
  const RenderScene scene = White();
  ShadeContext context;
  context.scene = &scene;
  TriangleSetup t;
  ASSERT_TRUE(SetupTriangle(At(0, 0, 0.5f, 1), At(32, 0, 0.5f, 1), At(0, 32, 0.5f, 1), 32, 32, &t));
  Framebuffer framebuffer;
  framebuffer.Resize(32, 32);
  DrawInTile(&framebuffer, TileRect{8, 0, 16, 8},
             [&](const TileTarget& tile) { RasterizeTriangle(t, context, tile); });
  EXPECT_EQ(framebuffer.Pixel(10, 2)[0], 255);
  EXPECT_EQ(framebuffer.Pixel(2, 2)[0], 0);
  EXPECT_EQ(framebuffer.Pixel(10, 10)[0], 0);
}

TEST(TileRaster, ClearPaintsTheSkyGradientAndFarDepth) {
  RenderScene scene = White();
  scene.sky_top = Eigen::Vector3f(0, 0, 1);
  scene.sky_horizon = Eigen::Vector3f(1, 0, 0);
  Framebuffer framebuffer;
  framebuffer.Resize(4, 11);
  std::fill(framebuffer.depth.begin(), framebuffer.depth.end(), 0.0f);
  std::vector<uint32_t> sky_rows;
  SkyRows(scene, 11, &sky_rows);
  DrawInTile(&framebuffer, TileRect{0, 0, 4, 11},
             [&](const TileTarget& tile) { ClearTile(sky_rows.data(), tile); });
  EXPECT_EQ(framebuffer.Pixel(2, 0)[2], 255);
  EXPECT_EQ(framebuffer.Pixel(2, 10)[0], 255);
  EXPECT_EQ(framebuffer.Pixel(2, 5)[0], 128);
  EXPECT_EQ(framebuffer.depth[7], 1.0f);
}

TEST(TileRaster, CopyOutWritesTheTileAndNothingElse) {
  for (int width = 1; width <= 40; ++width) {
    Framebuffer framebuffer;
    framebuffer.Resize(width + 3, 3);
    const TileRect rect{1, 1, 1 + width, 2};
    TileBuffer buffer(width);
    const TileTarget target = buffer.Target(rect);
    for (int x = rect.x0; x < rect.x1; ++x) *target.Rgbx(x, 1) = PackRgbx(x, 100 + x, 200 + x) | 0xff000000u;
    CopyOut(target, /*keep_depth=*/false, &framebuffer);
    for (int y = 0; y < 3; ++y) {
      for (int x = 0; x < width + 3; ++x) {
        const bool inside = y == 1 && x >= rect.x0 && x < rect.x1;
        const uint8_t* pixel = framebuffer.Pixel(x, y);
        EXPECT_EQ(pixel[0], inside ? x : 0) << width << ": " << x << "," << y;
        EXPECT_EQ(pixel[1], inside ? 100 + x : 0) << width << ": " << x << "," << y;
        EXPECT_EQ(pixel[2], inside ? 200 + x : 0) << width << ": " << x << "," << y;
      }
    }
  }
}

}  // namespace
}  // namespace flagsim::render
