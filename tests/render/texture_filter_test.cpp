// The pattern's filtering, on patterns whose right answer is known: a plain texture stays plain
// at every level, bilinear weights are exact between two texel centres and exact at each centre,
// a level is the mean of the one above, the level of detail follows texels per pixel, and a
// level of detail between two levels blends them linearly. All of it in light: the texels'
// sRGB bytes are decoded (to 16 bits: within 1 / kLinearOne of SrgbToLinear).
#include "server/render/texture_filter.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>

namespace flagsim::render {
namespace {

constexpr float kStep = 1.0f / kLinearOne;  ///< one step of the 16-bit linear texels

Texture Filled(int width, int height, const std::function<std::array<uint8_t, 3>(int, int)>& texel) {
  Texture texture;
  texture.width = width;
  texture.height = height;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      for (const uint8_t channel : texel(x, y)) texture.rgb.push_back(channel);
    }
  }
  return texture;
}

TEST(TextureFilter, APlainTextureIsPlainAtEveryLevelAndPlace) {
  FilteredTexture filtered;
  filtered.Assign(Filled(12, 7, [](int, int) { return std::array<uint8_t, 3>{51, 102, 204}; }));
  ASSERT_EQ(filtered.levels().size(), 4u);  // 12 x 7, 6 x 3, 3 x 1, 1 x 1
  EXPECT_EQ(filtered.levels().back().width, 1);
  for (const float lod : {0.0f, 0.3f, 1.0f, 2.7f, 3.0f}) {
    for (const float u : {-0.5f, 0.0f, 0.37f, 1.0f, 1.5f}) {
      float rgb[3];
      filtered.Sample(u, 0.61f, lod, rgb);
      EXPECT_NEAR(rgb[0], SrgbToLinear(51 / 255.0f), kStep);
      EXPECT_NEAR(rgb[1], SrgbToLinear(102 / 255.0f), kStep);
      EXPECT_NEAR(rgb[2], SrgbToLinear(204 / 255.0f), kStep);
    }
  }
}

TEST(TextureFilter, BilinearIsExactAtTexelCentresAndLinearBetween) {
  FilteredTexture filtered;  // black | white, one row
  filtered.Assign(Filled(2, 1, [](int x, int) { return std::array<uint8_t, 3>{uint8_t(255 * x), 0, 0}; }));
  float rgb[3];
  filtered.Sample(0.25f, 0.5f, 0, rgb);  // the first texel's centre
  EXPECT_FLOAT_EQ(rgb[0], 0);
  filtered.Sample(0.75f, 0.5f, 0, rgb);
  EXPECT_FLOAT_EQ(rgb[0], 1);
  for (const float t : {0.1f, 0.5f, 0.8f}) {  // between the centres: linear in u
    filtered.Sample(0.25f + 0.5f * t, 0.5f, 0, rgb);
    EXPECT_NEAR(rgb[0], t, 1e-6);
  }
  filtered.Sample(0.05f, 0.5f, 0, rgb);  // past the last centre: clamped to the edge texel
  EXPECT_FLOAT_EQ(rgb[0], 0);
}

TEST(TextureFilter, EachLevelIsTheMeanOfTheOneAbove) {
  FilteredTexture filtered;  // a 4 x 4 checker of 0 and 200: of their light, not of their bytes
  filtered.Assign(Filled(4, 4, [](int x, int y) {
    return std::array<uint8_t, 3>{uint8_t((x + y) % 2 ? 200 : 0), 0, 0};
  }));
  ASSERT_EQ(filtered.levels().size(), 3u);
  const uint64_t half = (kSrgbDecode[200] + 1) / 2;  // (0 + 200's light + 1) / 2, rounded as the levels are
  for (const uint64_t texel : filtered.levels()[1].texels) EXPECT_EQ(texel & 0xffff, half);
  EXPECT_EQ(filtered.levels()[2].texels[0] & 0xffff, half);
  float rgb[3];
  filtered.Sample(0.3f, 0.8f, 1, rgb);
  EXPECT_NEAR(rgb[0], 0.5f * SrgbToLinear(200 / 255.0f), kStep);
}

TEST(TextureFilter, TheLevelOfDetailFollowsTexelsPerPixel) {
  FilteredTexture filtered;
  filtered.Assign(Filled(64, 32, [](int, int) { return std::array<uint8_t, 3>{0, 0, 0}; }));
  const float texel_area = 1.0f / (64 * 32);             // (u, v) area of one texel
  EXPECT_EQ(filtered.LevelOfDetail(texel_area / 9), 0);  // magnified: the full-size level
  EXPECT_NEAR(filtered.LevelOfDetail(texel_area), 0, 1e-6);
  EXPECT_NEAR(filtered.LevelOfDetail(4 * texel_area), 1, 1e-6);  // 2 texels per pixel along each side
  EXPECT_NEAR(filtered.LevelOfDetail(16 * texel_area), 2, 1e-6);
  EXPECT_EQ(filtered.LevelOfDetail(1e6f), float(filtered.levels().size() - 1));  // the 1 x 1 level at most
  EXPECT_EQ(filtered.LevelOfDetail(0), 0);
}

TEST(TextureFilter, BetweenTwoLevelsTheyBlendLinearly) {
  FilteredTexture filtered;  // level 0: 0 | 200's light L; level 1: L / 2
  filtered.Assign(Filled(2, 1, [](int x, int) { return std::array<uint8_t, 3>{uint8_t(200 * x), 0, 0}; }));
  float rgb[3];
  filtered.Sample(0.25f, 0.5f, 0.25f, rgb);  // 0 at level 0, L / 2 at level 1: a quarter of the way
  EXPECT_NEAR(rgb[0], 0.25f * 0.5f * SrgbToLinear(200 / 255.0f), kStep);
}

}  // namespace
}  // namespace flagsim::render

namespace flagsim::render {
namespace {

TEST(TextureFilter, TransparentTexelsLendNoColourAndAlphaBlends) {
  // Left texel red and transparent, right texel blue and opaque: halfway between their centres
  // alpha is 1/2, and the straight colour is all blue (premultiplied filtering).
  Texture texture;
  texture.width = 2;
  texture.height = 1;
  texture.rgb = {255, 0, 0, 0, 0, 255};
  texture.alpha = {0, 255};
  FilteredTexture filtered;
  filtered.Assign(texture);
  EXPECT_TRUE(filtered.has_alpha());
  float rgb[3], alpha = 0;
  filtered.SamplerAt(0).SampleStraight(0.5f, 0.5f, rgb, &alpha);
  EXPECT_FLOAT_EQ(alpha, 0.5f);
  EXPECT_FLOAT_EQ(rgb[0], 0);
  EXPECT_FLOAT_EQ(rgb[1], 0);
  EXPECT_FLOAT_EQ(rgb[2], 1);
  texture.alpha.clear();  // opaque: no alpha, and the colour as it was
  filtered.Assign(texture);
  EXPECT_FALSE(filtered.has_alpha());
}

}  // namespace
}  // namespace flagsim::render
