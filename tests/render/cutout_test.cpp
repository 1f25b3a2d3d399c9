// A surface cut by its pattern's alpha (a person's image with transparent pixels): with one
// sample a pixel is drawn where alpha is at least 1/2; multisampled, alpha keeps round(alpha n)
// of the n samples (alpha to coverage), so the cut edge is smoothed. Where the surface is cut
// away it leaves no depth: what lies behind shows through.
#include <gtest/gtest.h>

#include <vector>

#include "server/render/sample_pattern.hpp"
#include "server/render/srgb.hpp"
#include "server/render/texture_filter.hpp"
#include "server/render/tile_raster.hpp"

namespace flagsim::render {
namespace {

constexpr int kSize = 32;  ///< px

ScreenVertex At(float x, float y, float z, float u, float v) {
  ScreenVertex vertex;
  vertex.x = x;
  vertex.y = y;
  vertex.z = z;
  vertex.inverse_w = 1;
  vertex.channels[0] = vertex.channels[1] = vertex.channels[2] = 1;  // D = 1, no specular
  vertex.channels[6] = u;
  vertex.channels[7] = v;
  return vertex;
}

/// The whole image as two triangles at depth z, of `material`, (u, v) from (0, 0) to (1, 1).
std::vector<TriangleSetup> Square(float z, int material, const SamplePattern& pattern) {
  const float s = float(kSize);
  const ScreenVertex corners[4] = {At(0, 0, z, 0, 0), At(s, 0, z, 1, 0), At(s, s, z, 1, 1),
                                   At(0, s, z, 0, 1)};
  std::vector<TriangleSetup> triangles;
  for (const auto& [a, b, c] : {std::array{0, 1, 2}, std::array{0, 2, 3}}) {
    TriangleSetup t;
    if (SetupTriangle(corners[a], corners[b], corners[c], kSize, kSize, &t, pattern.reach) ||
        SetupTriangle(corners[a], corners[c], corners[b], kSize, kSize, &t, pattern.reach)) {
      t.material = material;
      t.uv_area_per_pixel = 0;  // magnified: level 0
      triangles.push_back(t);
    }
  }
  return triangles;
}

/// An 8 x 1 white pattern, its left half transparent: magnified over 32 px, alpha ramps from 0
/// to 1 between the centres of texels 3 and 4 (px 14 and 18).
Texture HalfClear() {
  Texture texture;
  texture.width = 8;
  texture.height = 1;
  texture.rgb.assign(8 * 3, 255);
  texture.alpha = {0, 0, 0, 0, 255, 255, 255, 255};
  return texture;
}

/// The cut white square in front of a red one, in `mode`: row 10's green channel, which is 255
/// where white is drawn and 0 where red shows.
std::vector<int> GreenAcross(Antialiasing mode) {
  RenderScene scene;
  Material red, white;
  red.colour = Eigen::Vector3f(1, 0, 0);
  white.colour = Eigen::Vector3f(1, 1, 1);
  white.patterned = true;
  scene.materials = {red, white};
  FilteredTexture pattern;
  pattern.Assign(HalfClear());
  ShadeContext context;
  context.scene = &scene;
  context.pattern = &pattern;
  context.samples = PatternOf(mode);
  TileBuffer buffer(kSize, context.samples.count);
  const TileTarget target = buffer.Target(TileRect{0, 0, kSize, kSize});
  const std::vector<uint32_t> black(kSize, PackRgbx(0, 0, 0));
  ClearTile(black.data(), target);
  for (const TriangleSetup& t : Square(0.3f, 1, context.samples)) RasterizeTriangle(t, context, target);
  for (const TriangleSetup& t : Square(0.7f, 0, context.samples)) RasterizeTriangle(t, context, target);
  Framebuffer framebuffer;
  framebuffer.Resize(kSize, kSize);
  CopyOut(target, false, &framebuffer);
  std::vector<int> green;
  for (int x = 0; x < kSize; ++x) {
    EXPECT_EQ(framebuffer.Pixel(x, 10)[0], 255) << x;  // red or white: full red everywhere
    green.push_back(framebuffer.Pixel(x, 10)[1]);
  }
  return green;
}

TEST(Cutout, OneSampleDrawsWhereAlphaIsAtLeastAHalf) {
  const std::vector<int> green = GreenAcross(Antialiasing::kOff);
  for (int x = 0; x < kSize; ++x) EXPECT_EQ(green[size_t(x)], x >= 16 ? 255 : 0) << x;
}

TEST(Cutout, AlphaToCoverageSmoothsTheCutInSteps) {
  // Alpha at the centres of px 14 .. 17: 1/8, 3/8, 5/8, 7/8: 1, 2, 3 and 4 of 4 samples kept
  // (rounded half up), and the resolved pixel is that share of white over red, in light.
  const std::vector<int> green = GreenAcross(Antialiasing::kMsaa4);
  const auto share = [](int kept) { return int(EncodeSrgb16((kLinearOne * uint32_t(kept) + 2) / 4)); };
  for (int x = 0; x < kSize; ++x) {
    const int expected = x < 14 ? 0 : x < 18 ? share(x - 13) : 255;
    EXPECT_EQ(green[size_t(x)], expected) << x;
  }
}

}  // namespace
}  // namespace flagsim::render
