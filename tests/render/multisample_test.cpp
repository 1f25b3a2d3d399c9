// Multisampled tiles: each pixel shows the share of its samples a triangle covers, counted here
// without the rasterizer from the setup's exact edge functions; an edge's coverage is close to
// the area of the pixel it leaves inside; shared edges cover every sample once.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "server/render/multisample_raster.hpp"
#include "server/render/sample_pattern.hpp"
#include "server/render/srgb.hpp"
#include "server/render/tile_raster.hpp"

namespace flagsim::render {
namespace {

constexpr int kSize = 32;  ///< px, the test images' width and height
constexpr Antialiasing kMultisampled[] = {Antialiasing::kMsaa2, Antialiasing::kMsaa4, Antialiasing::kMsaa8};

/// Materials: 0 white, 1 red, 2 green; colour = material * D with D = 1 and no specular.
RenderScene Paints() {
  RenderScene scene;
  for (const Eigen::Vector3f& colour :
       {Eigen::Vector3f(1, 1, 1), Eigen::Vector3f(1, 0, 0), Eigen::Vector3f(0, 1, 0)}) {
    Material material;
    material.colour = colour;
    scene.materials.push_back(material);
  }
  return scene;
}

ScreenVertex At(float x, float y, float z = 0.5f) {
  ScreenVertex v;
  v.x = x;
  v.y = y;
  v.z = z;
  v.inverse_w = 1;
  v.channels[0] = v.channels[1] = v.channels[2] = 1;  // D
  return v;
}

/// The triangles drawn in order on black, in tiles of `tile` px, resolved.
Framebuffer Draw(const std::vector<TriangleSetup>& triangles, Antialiasing mode, int tile) {
  const RenderScene scene = Paints();
  ShadeContext context;
  context.scene = &scene;
  context.samples = PatternOf(mode);
  Framebuffer framebuffer;
  framebuffer.Resize(kSize, kSize);
  const std::vector<uint32_t> black(kSize, PackRgbx(0, 0, 0));
  TileBuffer buffer(tile, context.samples.count);
  for (int y0 = 0; y0 < kSize; y0 += tile) {
    for (int x0 = 0; x0 < kSize; x0 += tile) {
      const TileTarget target = buffer.Target(TileRect{x0, y0, x0 + tile, y0 + tile});
      ClearTile(black.data(), target);
      for (const TriangleSetup& t : triangles) RasterizeTriangle(t, context, target);
      CopyOut(target, false, &framebuffer);
    }
  }
  return framebuffer;
}

/// A pixel of which `inside` of n samples are full on (255) and the rest off (0), resolved: the
/// mean of their light, rounded, in sRGB.
uint32_t Resolved(int inside, int n) {
  return EncodeSrgb16((kLinearOne * uint32_t(inside) + uint32_t(n) / 2) / uint32_t(n));
}

/// Sample k of pixel (x, y) is inside t: all three edge functions, with their top-left bias,
/// at the sample's point in subpixels, worked out here in int64.
bool Inside(const TriangleSetup& t, int x, int y, SampleOffset offset) {
  const int64_t px = int64_t(x) * kSubpixels + kSubpixels / 2 + offset.x;
  const int64_t py = int64_t(y) * kSubpixels + kSubpixels / 2 + offset.y;
  for (int i = 0; i < 3; ++i) {
    const int64_t e = int64_t(t.edge_dx[i]) * (py - t.edge_y[i]) - int64_t(t.edge_dy[i]) * (px - t.edge_x[i]);
    if (e + t.edge_bias[i] < 0) return false;
  }
  return true;
}

TEST(Multisample, EachPixelShowsTheShareOfItsSamplesInside) {
  // Narrow triangles (walked in a window), large ones (edges walked a row at a time) and ones
  // covering whole tiles, in tiles of 8 and 32 px.
  std::mt19937 random(11);
  std::uniform_real_distribution<float> corner(-6.0f, 38.0f), offset(-6.0f, 6.0f);
  for (const Antialiasing mode : kMultisampled) {
    const SamplePattern pattern = PatternOf(mode);
    for (int trial = 0; trial < 60; ++trial) {
      const bool small = trial % 2 == 0;
      const float cx = corner(random), cy = corner(random);
      const ScreenVertex a = small ? At(cx, cy) : At(corner(random), corner(random));
      const ScreenVertex b =
          small ? At(cx + offset(random), cy + offset(random)) : At(corner(random), corner(random));
      const ScreenVertex c =
          small ? At(cx + offset(random), cy + offset(random)) : At(corner(random), corner(random));
      TriangleSetup t;
      if (!SetupTriangle(a, b, c, kSize, kSize, &t, pattern.reach)) continue;
      for (const int tile : {8, 32}) {
        const Framebuffer image = Draw({t}, mode, tile);
        for (int y = 0; y < kSize; ++y) {
          for (int x = 0; x < kSize; ++x) {
            int inside = 0;
            for (int k = 0; k < pattern.count; ++k) inside += Inside(t, x, y, pattern.offsets[k]);
            ASSERT_EQ(image.Pixel(x, y)[0], Resolved(inside, pattern.count))
                << AntialiasingNames()[int(mode)] << " trial " << trial << " tile " << tile << " at " << x
                << "," << y;
          }
        }
      }
    }
  }
}

/// The share of pixel (x, y)'s square below the line y = y0 + slope x (y down), by midpoint
/// sums over a fine grid.
double AreaBelow(int x, int y, double y0, double slope) {
  constexpr int kSteps = 256;
  int below = 0;
  for (int i = 0; i < kSteps; ++i) {
    for (int j = 0; j < kSteps; ++j) {
      const double px = x + (i + 0.5) / kSteps, py = y + (j + 0.5) / kSteps;
      below += py > y0 + slope * px;
    }
  }
  return double(below) / (kSteps * kSteps);
}

TEST(Multisample, AnEdgesCoverageIsCloseToTheAreaItLeavesInside) {
  // A white triangle below a shallow line across the image: where the line crosses a pixel, its
  // brightness follows the area below the line, within the error of n samples.
  const double y0 = 9.3, slope = 0.23;
  for (const Antialiasing mode :
       {Antialiasing::kOff, Antialiasing::kMsaa2, Antialiasing::kMsaa4, Antialiasing::kMsaa8}) {
    const SamplePattern pattern = PatternOf(mode);
    TriangleSetup t;
    ASSERT_TRUE(SetupTriangle(At(-8, float(y0 - 8 * slope)), At(40, float(y0 + 40 * slope)), At(16, 60),
                              kSize, kSize, &t, pattern.reach));
    const Framebuffer image = Draw({t}, mode, kSize);
    double error_sum = 0, error_max = 0;
    int edge_pixels = 0;
    for (int y = 0; y < kSize; ++y) {
      for (int x = 0; x < kSize; ++x) {
        const double area = AreaBelow(x, y, y0, slope);
        if (area <= 0 || area >= 1) continue;
        const double error = std::abs(SrgbToLinear(image.Pixel(x, y)[0] / 255.0f) - area);  // in light
        error_sum += error;
        error_max = std::max(error_max, error);
        ++edge_pixels;
      }
    }
    const double mean = error_sum / edge_pixels;
    // One sample is off by up to 1/2 of a pixel's light, n samples by about 1/(2n) on average.
    EXPECT_LT(mean, 0.6 / pattern.count) << AntialiasingNames()[int(mode)];
    EXPECT_LT(error_max, 1.5 / pattern.count + 0.01) << AntialiasingNames()[int(mode)];
    if (mode != Antialiasing::kOff) {
      EXPECT_LT(mean, 0.15) << "smoother than one sample";
    }
  }
}

TEST(Multisample, TwoTrianglesSharingAnEdgeCoverEverySampleOnce) {
  // A red and a green triangle making a square: along the diagonal each pixel's samples are
  // red or green, never both and never the black behind: a of n red, n - a green.
  for (const Antialiasing mode : kMultisampled) {
    const int reach = PatternOf(mode).reach;
    TriangleSetup red, green;
    ASSERT_TRUE(SetupTriangle(At(3.3f, 2.1f), At(29.6f, 4.7f), At(5.2f, 28.9f), kSize, kSize, &red, reach));
    ASSERT_TRUE(
        SetupTriangle(At(29.6f, 4.7f), At(27.4f, 30.2f), At(5.2f, 28.9f), kSize, kSize, &green, reach));
    red.material = 1;
    green.material = 2;
    const Framebuffer image = Draw({red, green}, mode, 8);
    int diagonal = 0;
    for (int y = 8; y < 24; ++y) {
      for (int x = 8; x < 24; ++x) {
        const uint8_t* p = image.Pixel(x, y);
        const int n = PatternOf(mode).count;
        bool shared = false;
        for (int a = 0; a <= n; ++a) shared |= p[0] == Resolved(a, n) && p[1] == Resolved(n - a, n);
        ASSERT_TRUE(shared) << AntialiasingNames()[int(mode)] << " at " << x << "," << y << ": " << int(p[0])
                            << ", " << int(p[1]);
        diagonal += p[0] > 0 && p[1] > 0;
      }
    }
    EXPECT_GT(diagonal, 10);  // the diagonal is blended, not stepped
  }
}

TEST(Multisample, TheNearerTriangleWinsEachSampleInEitherOrder) {
  // Two triangles crossing in depth: each sample shows the nearer, whichever is drawn first.
  for (const Antialiasing mode : kMultisampled) {
    const int reach = PatternOf(mode).reach;
    TriangleSetup red, green;
    ASSERT_TRUE(SetupTriangle(At(2, 2, 0.2f), At(30, 6, 0.8f), At(4, 30, 0.2f), kSize, kSize, &red, reach));
    ASSERT_TRUE(
        SetupTriangle(At(30, 2, 0.3f), At(28, 30, 0.3f), At(1, 14, 0.7f), kSize, kSize, &green, reach));
    red.material = 1;
    green.material = 2;
    EXPECT_EQ(Draw({red, green}, mode, 8).rgb, Draw({green, red}, mode, 32).rgb)
        << AntialiasingNames()[int(mode)];
  }
}

}  // namespace
}  // namespace flagsim::render
