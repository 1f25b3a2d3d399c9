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

/// What the per-pixel shading reads besides the triangle.
struct ShadeContext {
  const RenderScene* scene = nullptr;
  ShadingMode mode = ShadingMode::kGouraud;
  Eigen::Vector3f eye = Eigen::Vector3f::Zero();  ///< world frame, for per-pixel lighting
};

/// Sky gradient and far depth over the tile.
void ClearTile(const TileRect& tile, const RenderScene& scene, Framebuffer* framebuffer);

/// Draws the part of `triangle` inside `tile`.
///   kFlat, kGouraud: channels = diffuse rgb, specular rgb, u, v; colour = base * D + S
///   kPhong: channels = position xyz, normal xyz, u, v; Blinn-Phong per pixel
void RasterizeTriangle(const TriangleSetup& triangle, const TileRect& tile, const ShadeContext& context,
                       Framebuffer* framebuffer);

}  // namespace flagsim::render
