// Filling one tile: the sky behind, then triangles in order with a depth test, each pixel
// shaded by the frame's mode. Tiles share nothing, so any number run at once and the image is
// the same whatever the thread count. Multisampled, a tile holds a colour and a depth per
// sample (sample_pattern.hpp), and its pixels are their means when it is copied out.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "server/render/framebuffer.hpp"
#include "server/render/ground_shadow.hpp"
#include "server/render/mesh.hpp"
#include "server/render/sample_pattern.hpp"
#include "server/render/shading_mode.hpp"
#include "server/render/texture_filter.hpp"
#include "server/render/triangle_setup.hpp"

namespace flagsim::render {

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "TileTarget reads RGBX words as R, G, B bytes");

/// Pixels [x0, x1) x [y0, y1) of the image.
struct TileRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

/// Pixels a span may run past its end: spans are shaded in blocks of this many, and a block's
/// pixels past the span are read and written back unchanged.
constexpr int kSpanLanes = 8;

/// Where a tile is drawn: for each sample, its colour as RGBX words (bytes R, G, B, 0 in
/// memory) and its depth as floats, both in rows of `stride` pixels starting at pixel (x0, y0),
/// one sample's plane `plane` words after the last's. Each row has room for kSpanLanes - 1
/// pixels past x1 (see kSpanLanes).
struct TileTarget {
  TileRect rect;
  uint32_t* rgbx = nullptr;
  float* depth = nullptr;
  size_t stride = 0;  ///< pixels from one row to the next, rect.x1 - rect.x0 + kSpanLanes - 1 and up
  int samples = 1;    ///< per pixel
  size_t plane = 0;   ///< words from one sample's plane to the next
  int32_t* row_mask = nullptr;      ///< a row's worth (stride) of scratch, for multisampled rows
  uint32_t* row_colour = nullptr;   ///< the same

  uint32_t* Rgbx(int x, int y, int sample = 0) const {
    return rgbx + plane * size_t(sample) + size_t(y - rect.y0) * stride + size_t(x - rect.x0);
  }
  /// The pixel's R, G and B bytes.
  uint8_t* Pixel(int x, int y, int sample = 0) const { return reinterpret_cast<uint8_t*>(Rgbx(x, y, sample)); }
  float* Depth(int x, int y, int sample = 0) const {
    return depth + plane * size_t(sample) + size_t(y - rect.y0) * stride + size_t(x - rect.x0);
  }
};

/// Pixels of a tile's own, for tiles of up to size x size with `samples` samples each: black,
/// at far depth until drawn. Small enough to stay in cache while a tile is drawn.
class TileBuffer {
 public:
  explicit TileBuffer(int size, int samples = 1);
  /// The buffer as the target of `rect`.
  TileTarget Target(const TileRect& rect);

 private:
  size_t stride_, plane_;
  int samples_;
  std::vector<uint32_t> rgbx_;
  std::vector<float> depth_;
  std::vector<int32_t> row_mask_;
  std::vector<uint32_t> row_colour_;
};

/// A whole image's samples, colour and depth, as tiles leave them between the passes of a
/// frame drawn in passes (renderer.hpp).
struct SampleImage {
  int width = 0, height = 0, samples = 1;
  std::vector<uint32_t> rgbx;  ///< per sample a plane of width x height, rows top first
  std::vector<float> depth;    ///< the same

  void Resize(int new_width, int new_height, int new_samples);
};

/// The tile's samples into their place in `image`, or back out of it.
void SaveTile(const TileTarget& target, SampleImage* image);
void LoadTile(const SampleImage& image, const TileTarget& target);

/// RGBX packed the way TileTarget stores it: R in the lowest byte, the first in memory.
inline uint32_t PackRgbx(uint32_t r, uint32_t g, uint32_t b) { return r | g << 8 | b << 16; }

/// The drawn tile into its place in `framebuffer`: colour as RGB, each pixel the mean of its
/// samples (rounded), and depth too if `keep_depth` (the nearest of a pixel's samples).
void CopyOut(const TileTarget& target, bool keep_depth, Framebuffer* framebuffer);

/// What the per-pixel shading reads besides the triangle.
struct ShadeContext {
  const RenderScene* scene = nullptr;
  const FilteredTexture* pattern = nullptr;  ///< scene->pattern, filtered, for patterned materials
  ShadingMode mode = ShadingMode::kGouraud;
  Eigen::Vector3f eye = Eigen::Vector3f::Zero();  ///< world frame, for per-pixel lighting
  SamplePattern samples;                          ///< the target's samples (one: at the centre)
  const GroundShadow* shadow = nullptr;           ///< for materials that receive it; none: no shadow
};

/// The sky's RGBX colour on each row of an image `height` px high: sky_top on the first row,
/// blending linearly to sky_horizon on the last.
void SkyRows(const RenderScene& scene, int height, std::vector<uint32_t>* rows);

/// The sky (`sky_rows[y]` on image row y) and far depth over the tile, every sample.
void ClearTile(const uint32_t* sky_rows, const TileTarget& target);

/// Draws the part of `triangle` inside `tile`, at the samples of context.samples.
///   kFlat, kGouraud: channels = diffuse rgb, specular rgb, u, v; colour = base * D + S
///   kPhong: channels = position xyz, normal xyz, u, v; Blinn-Phong per pixel
void RasterizeTriangle(const TriangleSetup& triangle, const ShadeContext& context, const TileTarget& target);

}  // namespace flagsim::render
