#include "messages/tile_prediction.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

namespace flagsim {
namespace {

TEST(TilePrediction, ResidualsGiveThePixelsBack) {
  std::mt19937 random(7);
  for (const int width : {1, 2, 5, 64}) {
    for (const int height : {1, 3, 64}) {
      std::vector<uint8_t> pixels(size_t(width) * height * 3);
      for (uint8_t& byte : pixels) byte = static_cast<uint8_t>(random());
      std::vector<uint8_t> bytes;
      PredictRows(pixels, width, &bytes);
      UnpredictRows(width, &bytes);
      ASSERT_EQ(bytes, pixels) << width << " x " << height;
    }
  }
}

// Rows that repeat the one above leave nothing but the first row's steps; wrapping is modulo 256.
TEST(TilePrediction, RepeatedRowsLeaveZeros) {
  const int width = 3, height = 4;
  const std::vector<uint8_t> row = {10, 20, 30, 5, 25, 40, 255, 0, 30};
  std::vector<uint8_t> pixels(row.size() * height);
  for (int r = 0; r < height; ++r)
    std::copy(row.begin(), row.end(), pixels.begin() + std::ptrdiff_t(r * row.size()));
  std::vector<uint8_t> residuals;
  PredictRows(pixels, width, &residuals);
  const std::vector<uint8_t> first_row = {10, 20, 30, 251, 5, 10, 250, 231, 246};
  EXPECT_EQ(std::vector<uint8_t>(residuals.begin(), residuals.begin() + 9), first_row);
  for (size_t i = 9; i < residuals.size(); ++i) ASSERT_EQ(residuals[i], 0) << "byte " << i;
}

}  // namespace
}  // namespace flagsim
