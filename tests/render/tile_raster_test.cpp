#include "server/render/tile_raster.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "server/render/srgb.hpp"
#include "tests/render/tile_drawing.hpp"

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
  // D = x / 32 at every vertex (S = 0): each pixel shows the light (x + 0.5) / 32 in sRGB.
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
    const int expected = int(std::lround(255 * LinearToSrgb((x + 0.5f) / 32)));
    EXPECT_NEAR(framebuffer.Pixel(x, y)[0], expected, 1) << x << "," << y;
  }
  EXPECT_EQ(framebuffer.Pixel(31, 31)[0], 0);  // outside: untouched
}

TEST(TileRaster, EveryCoveredPixelGetsItsPlanesValueInAnyTiling) {
  // Small (walked in a window, shaded in blocks of any rows) and large triangles, perspective
  // correct: each covered pixel shows D = (D/w plane) / (1/w plane) encoded to sRGB, the planes
  // evaluated along the pixel's row first, and the rest stays black.
  const RenderScene scene = White();
  ShadeContext context;
  context.scene = &scene;
  std::mt19937 random(5);
  std::uniform_real_distribution<float> corner(-4.0f, 36.0f), offset(-7.0f, 7.0f), unit(0.0f, 1.0f);
  int narrow = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const float size = trial % 2 ? 1.0f : 4.0f;
    ScreenVertex v[3];
    const float x = corner(random), y = corner(random);
    for (ScreenVertex& vertex : v) {
      vertex = At(x + size * offset(random), y + size * offset(random), unit(random), unit(random));
      vertex.inverse_w = 0.5f + unit(random);
    }
    TriangleSetup t;
    if (!SetupTriangle(v[0], v[1], v[2], 32, 32, &t)) continue;
    narrow += t.narrow;
    for (const int tile : {32, 8, 5}) {
      Framebuffer framebuffer;
      framebuffer.Resize(32, 32);
      for (int y0 = 0; y0 < 32; y0 += tile) {
        for (int x0 = 0; x0 < 32; x0 += tile) {
          DrawInTile(&framebuffer, TileRect{x0, y0, std::min(x0 + tile, 32), std::min(y0 + tile, 32)},
                     [&](const TileTarget& target) { RasterizeTriangle(t, context, target); });
        }
      }
      for (int y = 0; y < 32; ++y) {
        int first = 0, last = -1;
        if (y < t.min_y || y > t.max_y || !RowSpan(t, y, &first, &last)) last = -1;
        const float fy = float(y - t.min_y);
        for (int px = 0; px < 32; ++px) {
          const float fx = float(px - t.min_x);
          const auto value = [&](const Plane& p) { return (p.origin + p.dy * fy) + p.dx * fx; };
          const float diffuse = value(t.channels[0]) * (1.0f / value(t.inverse_w));
          const int expected = int(EncodeSrgb(diffuse));
          ASSERT_EQ(framebuffer.Pixel(px, y)[0], px >= first && px <= last ? expected : 0)
              << "trial " << trial << " tile " << tile << " at " << px << "," << y;
        }
      }
    }
  }
  EXPECT_GT(narrow, 20);
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
    EXPECT_EQ(framebuffer.Pixel(3, 3)[0], EncodeSrgb(0.2f)) << near_first;
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
