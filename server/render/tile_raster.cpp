#include "tile_raster.hpp"

#include <algorithm>

namespace flagsim::render {
namespace {

uint8_t ToByte(float value) {
  const float scaled = value * 255.0f + 0.5f;
  return scaled <= 0 ? 0 : scaled >= 255 ? 255 : static_cast<uint8_t>(scaled);
}

/// The base colour at (u, v): the pattern's texel times the material's colour, or the colour.
Eigen::Vector3f BaseColour(const Material& material, const Texture& pattern, float u, float v) {
  if (!material.patterned) return material.colour;
  const uint8_t* texel = pattern.Sample(u, v);
  return material.colour.cwiseProduct(Eigen::Vector3f(texel[0], texel[1], texel[2]) * (1.0f / 255));
}

/// Interpolated channels at pixel (x, y): perspective-correct, channel = (channel / w) / (1 / w).
void Interpolate(const TriangleSetup& t, float fx, float fy, float out[kPlaneChannels]) {
  const float w = 1.0f / (t.inverse_w.origin + t.inverse_w.dx * fx + t.inverse_w.dy * fy);
  for (int k = 0; k < kPlaneChannels; ++k) {
    const Plane& p = t.channels[k];
    out[k] = (p.origin + p.dx * fx + p.dy * fy) * w;
  }
}

Eigen::Vector3f ShadePixel(const TriangleSetup& t, const ShadeContext& context, const float c[kPlaneChannels]) {
  const RenderScene& scene = *context.scene;
  const Material& material = scene.materials[t.material];
  const Eigen::Vector3f base = BaseColour(material, scene.pattern, c[6], c[7]);
  if (context.mode != ShadingMode::kPhong) {
    return base.cwiseProduct(Eigen::Vector3f(c[0], c[1], c[2])) + Eigen::Vector3f(c[3], c[4], c[5]);
  }
  Eigen::Vector3f normal = Eigen::Vector3f(c[3], c[4], c[5]).normalized();
  if (t.back_facing) normal = -normal;
  const Shade shade = ShadePoint(material, scene.lighting, Eigen::Vector3f(c[0], c[1], c[2]), normal, context.eye);
  return base.cwiseProduct(shade.diffuse) + shade.specular;
}

}  // namespace

void ClearTile(const TileRect& tile, const RenderScene& scene, Framebuffer* framebuffer) {
  for (int y = tile.y0; y < tile.y1; ++y) {
    const float t = framebuffer->height > 1 ? float(y) / (framebuffer->height - 1) : 0.0f;
    const Eigen::Vector3f sky = scene.sky_top + t * (scene.sky_horizon - scene.sky_top);
    const uint8_t rgb[3] = {ToByte(sky[0]), ToByte(sky[1]), ToByte(sky[2])};
    uint8_t* pixel = framebuffer->Pixel(tile.x0, y);
    for (int x = tile.x0; x < tile.x1; ++x, pixel += 3) std::copy(rgb, rgb + 3, pixel);
    std::fill_n(&framebuffer->depth[size_t(y) * framebuffer->width + tile.x0], tile.x1 - tile.x0, 1.0f);
  }
}

void RasterizeTriangle(const TriangleSetup& t, const TileRect& tile, const ShadeContext& context,
                       Framebuffer* framebuffer) {
  const int y_first = std::max(t.min_y, tile.y0), y_last = std::min(t.max_y, tile.y1 - 1);
  for (int y = y_first; y <= y_last; ++y) {
    int first = 0, last = 0;
    if (!RowSpan(t, y, &first, &last)) continue;
    first = std::max(first, tile.x0);
    last = std::min(last, tile.x1 - 1);
    const float fy = float(y - t.min_y);
    float* depth = &framebuffer->depth[size_t(y) * framebuffer->width];
    for (int x = first; x <= last; ++x) {
      const float fx = float(x - t.min_x);
      const float z = t.depth.origin + t.depth.dx * fx + t.depth.dy * fy;
      if (!(z < depth[x])) continue;
      depth[x] = z;
      float channels[kPlaneChannels];
      Interpolate(t, fx, fy, channels);
      const Eigen::Vector3f colour = ShadePixel(t, context, channels);
      uint8_t* pixel = framebuffer->Pixel(x, y);
      pixel[0] = ToByte(colour[0]);
      pixel[1] = ToByte(colour[1]);
      pixel[2] = ToByte(colour[2]);
    }
  }
}

}  // namespace flagsim::render
