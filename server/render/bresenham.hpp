// Bresenham's line: integer steps from one endpoint to the other in any of the eight octants,
// both endpoints drawn, one pixel per step of the major axis. The error term decides each
// minor-axis step: err = dx - dy tracks (twice) the distance of the ideal line from the pixel.
#pragma once

#include <cstdint>
#include <cstdlib>

#include "server/render/tile_raster.hpp"

namespace flagsim::render {

/// Calls plot(x, y, t) for every pixel from (x0, y0) to (x1, y1), t in [0, 1] along the line.
template <class Plot>
void Bresenham(int x0, int y0, int x1, int y1, Plot plot) {
  const int dx = std::abs(x1 - x0), dy = -std::abs(y1 - y0);
  const int sx = x0 < x1 ? 1 : -1, sy = y0 < y1 ? 1 : -1;
  const int steps = dx > -dy ? dx : -dy;
  int err = dx + dy;
  for (int step = 0;; ++step) {
    plot(x0, y0, steps > 0 ? float(step) / steps : 0.0f);
    if (x0 == x1 && y0 == y1) break;
    const int twice = 2 * err;
    if (twice >= dy) {
      err += dy;
      x0 += sx;
    }
    if (twice <= dx) {
      err += dx;
      y0 += sy;
    }
  }
}

/// A projected mesh edge: pixel endpoints, window depths, colour.
struct LineSetup {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  ///< px, the pixels the endpoints fall in
  float fx0 = 0, fy0 = 0, fx1 = 0, fy1 = 0;  ///< px, the endpoints themselves (Wu's line)
  float z0 = 0, z1 = 0;                ///< window depth at each end
  uint8_t rgb[3] = {0, 0, 0};
};

/// Draws the pixels of `line` that fall in `tile`, each where it is nearer than the depth
/// buffer (depth interpolated along the line), at every sample of a multisampled tile. A line
/// drawn tile by tile draws exactly the pixels it would draw whole.
inline void DrawLine(const LineSetup& line, const TileTarget& target) {
  const TileRect& tile = target.rect;
  Bresenham(line.x0, line.y0, line.x1, line.y1, [&](int x, int y, float t) {
    if (x < tile.x0 || x >= tile.x1 || y < tile.y0 || y >= tile.y1) return;
    const float z = line.z0 + t * (line.z1 - line.z0);
    for (int k = 0; k < target.samples; ++k) {
      float& depth = *target.Depth(x, y, k);
      if (!(z < depth)) continue;
      depth = z;
      uint8_t* pixel = target.Pixel(x, y, k);
      pixel[0] = line.rgb[0];
      pixel[1] = line.rgb[1];
      pixel[2] = line.rgb[2];
    }
  });
}

}  // namespace flagsim::render
