#include "tile_raster.hpp"

#include <algorithm>
#include <cstring>

namespace flagsim::render {
namespace {

/// 0..1 => 0..255, rounded and clamped; branch-free so that the loops using it vectorise.
uint32_t ToByte(float value) {
  return static_cast<uint32_t>(static_cast<int32_t>(std::min(std::max(value * 255.0f + 0.5f, 0.0f), 255.0f)));
}

/// A plane's value along one row: at + step * (x - min_x).
struct RowPlane {
  float at, step;
};

RowPlane AlongRow(const Plane& plane, float fy) { return RowPlane{plane.origin + plane.dy * fy, plane.dx}; }

/// Gouraud and flat: colour = base * D + S with D, S the interpolated light (channels 0-5) and
/// base the material's colour, times the pattern's texel at (u, v) (channels 6, 7) when
/// `kPatterned`. Perspective-correct: each channel is (channel / w) / (1 / w). Shades a block
/// of kSpanLanes pixels at once, each step a loop over the lanes so that it vectorises.
template <bool kPatterned>
class BlockShader {
 public:
  static constexpr int kChannels = kPatterned ? 8 : 6;

  BlockShader(const TriangleSetup& t, const Material& material, const RgbxTexture& pattern, float fy)
      : inverse_w_(AlongRow(t.inverse_w, fy)),
        base_{material.colour[0], material.colour[1], material.colour[2]},
        pattern_(pattern) {
    for (int k = 0; k < kChannels; ++k) channel_[k] = AlongRow(t.channels[k], fy);
  }

  /// The RGBX colours at fx[i] pixels from the box's first column.
  void Shade(const float fx[kSpanLanes], uint32_t rgbx[kSpanLanes]) const {
    float w[kSpanLanes], c[kChannels][kSpanLanes];
#pragma omp simd
    for (int i = 0; i < kSpanLanes; ++i) w[i] = 1.0f / (inverse_w_.at + inverse_w_.step * fx[i]);
    for (int k = 0; k < kChannels; ++k) {
#pragma omp simd
      for (int i = 0; i < kSpanLanes; ++i) c[k][i] = (channel_[k].at + channel_[k].step * fx[i]) * w[i];
    }
    float base[3][kSpanLanes];
    if constexpr (kPatterned) {
      Tint(c[6], c[7], base);
    } else {
#pragma omp simd
      for (int i = 0; i < kSpanLanes; ++i) {
        for (int j = 0; j < 3; ++j) base[j][i] = base_[j];
      }
    }
#pragma omp simd
    for (int i = 0; i < kSpanLanes; ++i) {
      rgbx[i] = PackRgbx(ToByte(base[0][i] * c[0][i] + c[3][i]), ToByte(base[1][i] * c[1][i] + c[4][i]),
                         ToByte(base[2][i] * c[2][i] + c[5][i]));
    }
  }

 private:
  /// base * (texel / 255) per channel, the texel at (u[i], v[i]) picked as Texture::Sample does.
  void Tint(const float u[kSpanLanes], const float v[kSpanLanes], float base[3][kSpanLanes]) const {
    const int width = pattern_.width, height = pattern_.height;
    int32_t index[kSpanLanes];
#pragma omp simd
    for (int i = 0; i < kSpanLanes; ++i) {
      int x = static_cast<int>(u[i] * width), y = static_cast<int>(v[i] * height);
      x = x < 0 ? 0 : x >= width ? width - 1 : x;
      y = y < 0 ? 0 : y >= height ? height - 1 : y;
      index[i] = y * width + x;
    }
    const uint32_t* texels = pattern_.texels.data();
#pragma omp simd
    for (int i = 0; i < kSpanLanes; ++i) {
      const uint32_t texel = texels[index[i]];
      for (int j = 0; j < 3; ++j) base[j][i] = base_[j] * (float(texel >> 8 * j & 0xff) * (1.0f / 255));
    }
  }

  RowPlane inverse_w_;
  RowPlane channel_[kChannels];
  float base_[3];
  const RgbxTexture& pattern_;
};

/// The n pixels of a row from fx0 pixels past the box's first column, kSpanLanes at a time:
/// the depth test, then where any pixel of the block is in front, the block's colours stored
/// to those pixels. Lanes past the span repeat its last pixel and are masked off. depth and
/// rgbx point at the span's first pixel.
template <bool kPatterned>
void FillSpan(const BlockShader<kPatterned>& shader, const RowPlane& z, float fx0, int n, float* depth,
              uint32_t* rgbx) {
  for (int start = 0; start < n; start += kSpanLanes, depth += kSpanLanes, rgbx += kSpanLanes) {
    float fx[kSpanLanes];
    int32_t in_front[kSpanLanes];
    int any = 0;
#pragma omp simd reduction(| : any)
    for (int i = 0; i < kSpanLanes; ++i) {
      fx[i] = fx0 + float(std::min(start + i, n - 1));
      const float here = z.at + z.step * fx[i];
      const bool nearer = start + i < n && here < depth[i];
      depth[i] = nearer ? here : depth[i];
      in_front[i] = nearer;
      any |= nearer;
    }
    if (!any) continue;
    uint32_t colour[kSpanLanes];
    shader.Shade(fx, colour);
#pragma omp simd
    for (int i = 0; i < kSpanLanes; ++i) rgbx[i] = in_front[i] ? colour[i] : rgbx[i];
  }
}

template <bool kPatterned>
void FillSpanInterpolated(const TriangleSetup& t, const Material& material, const RgbxTexture& pattern,
                          float fy, int first, int last, float* depth, uint32_t* rgbx) {
  const BlockShader<kPatterned> shader(t, material, pattern, fy);
  FillSpan(shader, AlongRow(t.depth, fy), float(first - t.min_x), last - first + 1, depth, rgbx);
}

/// Phong: channels are world position (0-2) and normal (3-5); Blinn-Phong per pixel.
/// depth and rgbx point at pixel `first`.
void FillSpanPhong(const TriangleSetup& t, const ShadeContext& context, float fy, int first, int last,
                   float* depth, uint32_t* rgbx) {
  const RenderScene& scene = *context.scene;
  const Material& material = scene.materials[t.material];
  const RowPlane z = AlongRow(t.depth, fy), inverse_w = AlongRow(t.inverse_w, fy);
  RowPlane channel[kPlaneChannels];
  for (int k = 0; k < kPlaneChannels; ++k) channel[k] = AlongRow(t.channels[k], fy);
  for (int x = first; x <= last; ++x) {
    const float fx = float(x - t.min_x);
    const float depth_here = z.at + z.step * fx;
    float& depth_there = depth[x - first];
    if (!(depth_here < depth_there)) continue;
    depth_there = depth_here;
    const float w = 1.0f / (inverse_w.at + inverse_w.step * fx);
    float c[kPlaneChannels];
    for (int k = 0; k < kPlaneChannels; ++k) c[k] = (channel[k].at + channel[k].step * fx) * w;
    Eigen::Vector3f normal = Eigen::Vector3f(c[3], c[4], c[5]).normalized();
    if (t.back_facing) normal = -normal;
    const Shade shade =
        ShadePoint(material, scene.lighting, Eigen::Vector3f(c[0], c[1], c[2]), normal, context.eye);
    Eigen::Vector3f base = material.colour;
    if (material.patterned) {
      const uint8_t* texel = scene.pattern.Sample(c[6], c[7]);
      base = base.cwiseProduct(Eigen::Vector3f(texel[0], texel[1], texel[2]) * (1.0f / 255));
    }
    const Eigen::Vector3f colour = base.cwiseProduct(shade.diffuse) + shade.specular;
    rgbx[x - first] = PackRgbx(ToByte(colour[0]), ToByte(colour[1]), ToByte(colour[2]));
  }
}

}  // namespace

TileBuffer::TileBuffer(int size)
    : stride_(size_t(size) + kSpanLanes - 1),
      rgbx_(stride_ * size, PackRgbx(0, 0, 0)),
      depth_(stride_ * size, 1.0f) {}

TileTarget TileBuffer::Target(const TileRect& rect, int image_height) {
  TileTarget target;
  target.rect = rect;
  target.image_height = image_height;
  target.rgbx = rgbx_.data();
  target.depth = depth_.data();
  target.stride = stride_;
  return target;
}

void RgbxTexture::Assign(const Texture& texture) {
  width = texture.width;
  height = texture.height;
  texels.resize(size_t(width) * height);
  for (size_t i = 0; i < texels.size(); ++i) {
    texels[i] = PackRgbx(texture.rgb[3 * i], texture.rgb[3 * i + 1], texture.rgb[3 * i + 2]);
  }
}

void CopyOut(const TileTarget& target, bool keep_depth, Framebuffer* framebuffer) {
  const TileRect& tile = target.rect;
  const int pixels = tile.x1 - tile.x0;
  for (int y = tile.y0; y < tile.y1; ++y) {
    const uint8_t* __restrict rgbx = target.Pixel(tile.x0, y);
    uint8_t* __restrict rgb = framebuffer->Pixel(tile.x0, y);
#pragma omp simd
    for (int i = 0; i < pixels; ++i) {
      for (int k = 0; k < 3; ++k) rgb[3 * i + k] = rgbx[4 * i + k];
    }
    if (keep_depth) {
      std::memcpy(&framebuffer->depth[size_t(y) * framebuffer->width + tile.x0], target.Depth(tile.x0, y),
                  size_t(pixels) * sizeof(float));
    }
  }
}

void ClearTile(const RenderScene& scene, const TileTarget& target) {
  const TileRect& tile = target.rect;
  const int pixels = tile.x1 - tile.x0;
  for (int y = tile.y0; y < tile.y1; ++y) {
    const float t = target.image_height > 1 ? float(y) / (target.image_height - 1) : 0.0f;
    const Eigen::Vector3f sky = scene.sky_top + t * (scene.sky_horizon - scene.sky_top);
    const uint32_t colour = PackRgbx(ToByte(sky[0]), ToByte(sky[1]), ToByte(sky[2]));
    uint32_t* rgbx = target.Rgbx(tile.x0, y);
    float* depth = target.Depth(tile.x0, y);
#pragma omp simd
    for (int i = 0; i < pixels; ++i) {
      rgbx[i] = colour;
      depth[i] = 1.0f;
    }
  }
}

void RasterizeTriangle(const TriangleSetup& t, const ShadeContext& context, const TileTarget& target) {
  const TileRect& tile = target.rect;
  const Material& material = context.scene->materials[t.material];
  const int y_first = std::max(t.min_y, tile.y0), y_last = std::min(t.max_y, tile.y1 - 1);
  if (y_first > y_last) return;
  RowSpans spans(t, y_first);
  for (int y = y_first; y <= y_last; ++y, spans.NextRow()) {
    int first = 0, last = 0;
    if (!spans.Span(&first, &last)) continue;
    first = std::max(first, tile.x0);
    last = std::min(last, tile.x1 - 1);
    if (first > last) continue;
    const float fy = float(y - t.min_y);
    float* depth = target.Depth(first, y);
    uint32_t* rgbx = target.Rgbx(first, y);
    if (context.mode == ShadingMode::kPhong) {
      FillSpanPhong(t, context, fy, first, last, depth, rgbx);
    } else if (material.patterned) {
      FillSpanInterpolated<true>(t, material, *context.pattern, fy, first, last, depth, rgbx);
    } else {
      FillSpanInterpolated<false>(t, material, *context.pattern, fy, first, last, depth, rgbx);
    }
  }
}

}  // namespace flagsim::render
