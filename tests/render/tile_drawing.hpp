// Drawing into part of a framebuffer the way the renderer draws a tile: through a TileBuffer,
// with the framebuffer's pixels copied in first and the result copied back out.
#pragma once

#include <algorithm>
#include <cstring>

#include "server/render/tile_raster.hpp"

namespace flagsim::render {

/// Calls draw(target) on a tile holding `framebuffer`'s pixels in `rect`, then copies the tile
/// (colour and depth) back.
template <class Draw>
void DrawInTile(Framebuffer* framebuffer, const TileRect& rect, Draw draw) {
  TileBuffer buffer(std::max(rect.x1 - rect.x0, rect.y1 - rect.y0));
  const TileTarget target = buffer.Target(rect);
  for (int y = rect.y0; y < rect.y1; ++y) {
    for (int x = rect.x0; x < rect.x1; ++x) {
      std::memcpy(target.Pixel(x, y), framebuffer->Pixel(x, y), 3);
      *target.Depth(x, y) = framebuffer->depth[size_t(y) * framebuffer->width + x];
    }
  }
  draw(target);
  CopyOut(target, /*keep_depth=*/true, framebuffer);
}

}  // namespace flagsim::render
