#include "server/render/srgb.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace flagsim::render {
namespace {

TEST(Srgb, TheTransferFunctionsAreEachOthersInverse) {
  for (int i = 0; i <= 1000; ++i) {
    const float s = i / 1000.0f;
    EXPECT_NEAR(LinearToSrgb(SrgbToLinear(s)), s, 2e-6f) << s;
  }
  // The standard's anchors: the ends, mid grey, and the linear segment near black.
  EXPECT_EQ(SrgbToLinear(0), 0.0f);
  EXPECT_FLOAT_EQ(SrgbToLinear(1), 1.0f);
  EXPECT_NEAR(SrgbToLinear(0.5f), 0.21404f, 1e-5f);
  EXPECT_NEAR(SrgbToLinear(0.04f), 0.04f / 12.92f, 1e-7f);
}

TEST(Srgb, EveryByteComesBackThroughItsLight) {
  for (int b = 0; b < 256; ++b) {
    EXPECT_EQ(EncodeSrgb(SrgbToLinear(b / 255.0f)), uint32_t(b)) << b;  // through the float
    EXPECT_EQ(EncodeSrgb16(kSrgbDecode[size_t(b)]), uint32_t(b)) << b;  // through 16-bit light
  }
}

TEST(Srgb, EncodingRoundsToTheNearestByteAndClamps) {
  for (int i = 0; i <= 200; ++i) {
    const float linear = i / 200.0f;
    EXPECT_NEAR(double(EncodeSrgb(linear)), 255.0 * LinearToSrgb(linear), 0.75) << linear;
  }
  EXPECT_EQ(EncodeSrgb(-0.3f), 0u);
  EXPECT_EQ(EncodeSrgb(1.7f), 255u);
  EXPECT_EQ(EncodeSrgb16(70000), 255u);
}

}  // namespace
}  // namespace flagsim::render
