// Xiaolin Wu's line: an anti-aliased line one pixel wide. Along the major axis, one step a
// pixel; across it, the ideal line's centre falls between two pixel centres, and each of the
// two gets the share of the line's width that lies on its side:
//
//   c = y0 + (x + 1/2 - x0) dy/dx - 1/2   the line's centre in the pixel rows' index space
//   row floor(c) gets 1 - (c - floor(c)), row floor(c) + 1 gets c - floor(c)
//
// so the two shares always sum to one and a line's brightness does not crawl as it moves by a
// fraction of a pixel. Endpoints are drawn whole (mesh edges meet end to end). The wireframe
// uses it when frames are anti-aliased; Bresenham's line (bresenham.hpp) otherwise.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

#include "server/render/bresenham.hpp"
#include "server/render/srgb.hpp"
#include "server/render/tile_raster.hpp"

namespace flagsim::render {

/// Calls plot(x, y, t, coverage) for the pixels of the line from (x0, y0) to (x1, y1) (px, the
/// image's corner at 0), t in [0, 1] along it, coverage in [0, 1].
template <class Plot>
void WuLine(float x0, float y0, float x1, float y1, Plot plot) {
  const bool steep = std::abs(y1 - y0) > std::abs(x1 - x0);
  if (steep) {  // walk y: swap the axes, and swap them back when plotting
    std::swap(x0, y0);
    std::swap(x1, y1);
  }
  const bool reversed = x0 > x1;
  if (reversed) {
    std::swap(x0, x1);
    std::swap(y0, y1);
  }
  const float gradient = x1 > x0 ? (y1 - y0) / (x1 - x0) : 0.0f;
  const int first = int(std::floor(x0)), last = int(std::floor(x1));
  for (int x = first; x <= last; ++x) {
    const float centre = y0 + (float(x) + 0.5f - x0) * gradient - 0.5f;
    const float below = std::floor(centre), share = centre - below;
    const float along = last > first ? float(x - first) / float(last - first) : 0.0f;
    const float t = reversed ? 1.0f - along : along;
    const int row = int(below);
    if (steep) {
      plot(row, x, t, 1.0f - share);
      plot(row + 1, x, t, share);
    } else {
      plot(x, row, t, 1.0f - share);
      plot(x, row + 1, t, share);
    }
  }
}

/// floor(a / 256), for either sign.
inline int FloorDiv256(int a) { return a >= 0 ? a / 256 : -((255 - a) / 256); }

/// Draws the pixels of `line` that fall in `tile` as Wu's line, each blended over every
/// sample it is nearer than, by its coverage, in light: colour + (line - colour) coverage, in
/// 16-bit linear with the coverage in 256ths, encoded to sRGB again. Its depth is written where
/// it covers at least half the pixel. Tile by tile, it draws what it would draw whole.
inline void DrawSmoothLine(const LineSetup& line, const TileTarget& target) {
  const TileRect& tile = target.rect;
  WuLine(line.fx0, line.fy0, line.fx1, line.fy1, [&](int x, int y, float t, float coverage) {
    if (x < tile.x0 || x >= tile.x1 || y < tile.y0 || y >= tile.y1 || coverage <= 0) return;
    const float z = line.z0 + t * (line.z1 - line.z0);
    const int weight = int(coverage * 256.0f + 0.5f);  // of 256
    for (int k = 0; k < target.samples; ++k) {
      float& depth = *target.Depth(x, y, k);
      if (!(z < depth)) continue;
      if (weight >= 128) depth = z;
      uint8_t* pixel = target.Pixel(x, y, k);
      for (int c = 0; c < 3; ++c) {
        const int under = int(kSrgbDecode[pixel[c]]), over = int(kSrgbDecode[line.rgb[c]]);
        pixel[c] = uint8_t(EncodeSrgb16(uint32_t(under + FloorDiv256((over - under) * weight + 128))));
      }
    }
  });
}

}  // namespace flagsim::render
