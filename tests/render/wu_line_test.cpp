#include "server/render/wu_line.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <tuple>
#include <utility>

#include "tests/render/tile_drawing.hpp"

namespace flagsim::render {
namespace {

/// The line's coverage per pixel, summed where a pixel is plotted twice.
std::map<std::pair<int, int>, float> Coverage(float x0, float y0, float x1, float y1) {
  std::map<std::pair<int, int>, float> coverage;
  WuLine(x0, y0, x1, y1, [&](int x, int y, float, float share) { coverage[{x, y}] += share; });
  return coverage;
}

TEST(WuLine, ALineThroughPixelCentresCoversItsRowWhole) {
  const auto coverage = Coverage(2.5f, 7.5f, 12.5f, 7.5f);
  for (int x = 2; x <= 12; ++x) {
    EXPECT_FLOAT_EQ(coverage.at({x, 7}), 1.0f) << x;
    EXPECT_FLOAT_EQ(coverage.at({x, 8}), 0.0f) << x;
  }
}

TEST(WuLine, ALineBetweenRowsIsSharedByTheTwoByDistance) {
  // A quarter of a pixel below row 7's centres: 3/4 in row 7, 1/4 in row 8.
  const auto coverage = Coverage(0.5f, 7.75f, 20.5f, 7.75f);
  for (int x = 0; x <= 20; ++x) {
    EXPECT_FLOAT_EQ(coverage.at({x, 7}), 0.75f) << x;
    EXPECT_FLOAT_EQ(coverage.at({x, 8}), 0.25f) << x;
  }
}

TEST(WuLine, EachStepOfTheMajorAxisCarriesOnePixelOfLight) {
  // Shallow and steep, in every direction: per column (shallow) or row (steep), the shares sum to one.
  for (const auto& [x0, y0, x1, y1] :
       {std::tuple{1.3f, 2.9f, 27.8f, 13.1f}, std::tuple{27.8f, 13.1f, 1.3f, 2.9f},
        std::tuple{4.2f, 1.1f, 9.7f, 28.4f}, std::tuple{9.7f, 28.4f, 4.2f, 1.1f}}) {
    const bool steep = std::abs(y1 - y0) > std::abs(x1 - x0);
    std::map<int, float> per_step;
    WuLine(x0, y0, x1, y1, [&](int x, int y, float, float share) { per_step[steep ? y : x] += share; });
    const int first = int(std::floor(steep ? std::min(y0, y1) : std::min(x0, x1)));
    const int last = int(std::floor(steep ? std::max(y0, y1) : std::max(x0, x1)));
    EXPECT_EQ(per_step.size(), size_t(last - first + 1));
    for (const auto& [step, sum] : per_step) EXPECT_NEAR(sum, 1.0f, 1e-6f) << step;
  }
}

TEST(WuLine, ASteepLineIsTheShallowOneTransposed) {
  const auto shallow = Coverage(3.2f, 5.6f, 25.1f, 14.3f);
  const auto steep = Coverage(5.6f, 3.2f, 14.3f, 25.1f);
  ASSERT_EQ(shallow.size(), steep.size());
  for (const auto& [pixel, share] : shallow) EXPECT_FLOAT_EQ(steep.at({pixel.second, pixel.first}), share);
}

TEST(DrawSmoothLine, BlendsByCoverageAndTileByTileDrawsWhatTheWholeLineDraws) {
  LineSetup line;
  line.fx0 = 2.3f;
  line.fy0 = 27.6f;
  line.fx1 = 37.2f;
  line.fy1 = 3.4f;
  line.x0 = 2, line.y0 = 27, line.x1 = 37, line.y1 = 3;
  line.z0 = 0.2f;
  line.z1 = 0.6f;
  line.rgb[0] = 255;
  Framebuffer whole, tiled;
  whole.Resize(40, 30);
  tiled.Resize(40, 30);
  DrawInTile(&whole, TileRect{0, 0, 40, 30}, [&](const TileTarget& tile) { DrawSmoothLine(line, tile); });
  for (int y = 0; y < 30; y += 8) {
    for (int x = 0; x < 40; x += 8) {
      DrawInTile(&tiled, TileRect{x, y, std::min(x + 8, 40), std::min(y + 8, 30)},
                 [&](const TileTarget& tile) { DrawSmoothLine(line, tile); });
    }
  }
  EXPECT_EQ(whole.rgb, tiled.rgb);
  EXPECT_EQ(whole.depth, tiled.depth);
  // Over black, each pixel's red is its coverage of the line's light (in 256ths, rounded), in sRGB.
  WuLine(line.fx0, line.fy0, line.fx1, line.fy1, [&](int x, int y, float, float share) {
    if (x < 0 || x >= 40 || y < 0 || y >= 30) return;
    const uint32_t weight = uint32_t(share * 256.0f + 0.5f);
    EXPECT_EQ(whole.Pixel(x, y)[0], EncodeSrgb16((kLinearOne * weight + 128) / 256)) << x << "," << y;
  });
}

}  // namespace
}  // namespace flagsim::render
