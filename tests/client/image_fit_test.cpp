#include "client/image_fit.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

namespace flagsim {
namespace {

std::vector<uint8_t> Uniform(int width, int height, uint8_t r, uint8_t g, uint8_t b) {
  std::vector<uint8_t> rgb;
  for (int i = 0; i < width * height; ++i) rgb.insert(rgb.end(), {r, g, b});
  return rgb;
}

/// The pixel at (x, y) of a `width` wide RGB8 image, as one number 0xRRGGBB.
uint32_t At(const std::vector<uint8_t>& rgb, int width, int x, int y) {
  const size_t i = (size_t(y) * width + x) * 3;
  return uint32_t(rgb[i]) << 16 | uint32_t(rgb[i + 1]) << 8 | rgb[i + 2];
}

TEST(FitImage, TheSameSizeIsTheSameImage) {
  std::vector<uint8_t> rgb(7 * 5 * 3);
  for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = uint8_t(i * 37);
  EXPECT_EQ(FitImage(rgb.data(), 7, 5, 7, 5), rgb);
}

// 8 x 4 into 16 x 16: twice the size, 16 x 8, centred between black bars of 4 rows each.
TEST(FitImage, AWiderImageGetsBarsAboveAndBelow) {
  const std::vector<uint8_t> red = Uniform(8, 4, 200, 10, 20);
  const std::vector<uint8_t> fitted = FitImage(red.data(), 8, 4, 16, 16);
  ASSERT_EQ(fitted.size(), 16u * 16 * 3);
  for (int y = 0; y < 16; ++y) {
    for (int x = 0; x < 16; ++x) {
      EXPECT_EQ(At(fitted, 16, x, y), y >= 4 && y < 12 ? 0xC80A14u : 0u) << x << ", " << y;
    }
  }
}

// 4 x 8 into 8 x 8: the same height, 4 columns wide, centred between bars of 2 columns.
TEST(FitImage, ATallerImageGetsBarsAtTheSides) {
  const std::vector<uint8_t> green = Uniform(4, 8, 0, 255, 0);
  const std::vector<uint8_t> fitted = FitImage(green.data(), 4, 8, 8, 8);
  for (int y = 0; y < 8; ++y) {
    for (int x = 0; x < 8; ++x) EXPECT_EQ(At(fitted, 8, x, y), x >= 2 && x < 6 ? 0x00FF00u : 0u);
  }
}

// Halved, a picture keeps its halves: white on the left, black on the right, a blend between.
TEST(FitImage, ShrinkingKeepsWhereThingsAre) {
  std::vector<uint8_t> halves(8 * 4 * 3, 0);
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 4; ++x) std::fill_n(&halves[(size_t(y) * 8 + x) * 3], 3, uint8_t(255));
  }
  const std::vector<uint8_t> fitted = FitImage(halves.data(), 8, 4, 4, 2);
  for (int y = 0; y < 2; ++y) {
    EXPECT_EQ(At(fitted, 4, 0, y), 0xFFFFFFu);
    EXPECT_GT(At(fitted, 4, 1, y), At(fitted, 4, 2, y));
    EXPECT_EQ(At(fitted, 4, 3, y), 0u);
  }
}

}  // namespace
}  // namespace flagsim
