// Filling one tile: the sky behind, then triangles in order with a depth test, each pixel
// shaded by the frame's mode. Tiles share nothing, so any number run at once and the image is
// the same whatever the thread count.
#pragma once

#include <Eigen/Core>

#include "framebuffer.hpp"
#include "mesh.hpp"
#include "shading_mode.hpp"
#include "triangle_setup.hpp"

namespace flagsim::render {

/// Pixels [x0, x1) x [y0, y1) of the image.
struct TileRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

/// Where a tile is drawn: its pixels, stored in rows of `rgb_stride` bytes and `depth_stride`
/// floats starting at pixel (x0, y0). The renderer points it at a small buffer of its own,
/// which stays in cache while the tile is drawn; tests may point it into a Framebuffer.
struct TileTarget {
  TileRect rect;
  int image_height = 0;  ///< px, for the sky's gradient
  uint8_t* rgb = nullptr;
  size_t rgb_stride = 0;  ///< bytes from one row to the next
  float* depth = nullptr;
  size_t depth_stride = 0;  ///< floats from one row to the next

  uint8_t* Pixel(int x, int y) const {
    return rgb + size_t(y - rect.y0) * rgb_stride + size_t(x - rect.x0) * 3;
  }
  float* Depth(int x, int y) const {
    return depth + size_t(y - rect.y0) * depth_stride + size_t(x - rect.x0);
  }

  /// The part `rect` of a whole framebuffer.
  static TileTarget Into(Framebuffer* framebuffer, const TileRect& rect) {
    TileTarget target;
    target.rect = rect;
    target.image_height = framebuffer->height;
    target.rgb = framebuffer->Pixel(rect.x0, rect.y0);
    target.rgb_stride = size_t(framebuffer->width) * 3;
    target.depth = &framebuffer->depth[size_t(rect.y0) * framebuffer->width + rect.x0];
    target.depth_stride = size_t(framebuffer->width);
    return target;
  }
};

/// What the per-pixel shading reads besides the triangle.
struct ShadeContext {
  const RenderScene* scene = nullptr;
  ShadingMode mode = ShadingMode::kGouraud;
  Eigen::Vector3f eye = Eigen::Vector3f::Zero();  ///< world frame, for per-pixel lighting
};

/// Sky gradient and far depth over the tile.
void ClearTile(const RenderScene& scene, const TileTarget& target);

/// Draws the part of `triangle` inside `tile`.
///   kFlat, kGouraud: channels = diffuse rgb, specular rgb, u, v; colour = base * D + S
///   kPhong: channels = position xyz, normal xyz, u, v; Blinn-Phong per pixel
void RasterizeTriangle(const TriangleSetup& triangle, const ShadeContext& context, const TileTarget& target);

}  // namespace flagsim::render
