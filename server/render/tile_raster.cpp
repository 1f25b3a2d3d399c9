#include "tile_raster.hpp"

#include <algorithm>
#include <cstring>

namespace flagsim::render {
namespace {

/// 0..1 => 0..255, rounded and clamped; branch-free so that the loops using it vectorise.
uint8_t ToByte(float value) {
  return static_cast<uint8_t>(std::min(std::max(value * 255.0f + 0.5f, 0.0f), 255.0f));
}

/// A plane's value along one row: at + step * (x - min_x).
struct RowPlane {
  float at, step;
};

RowPlane AlongRow(const Plane& plane, float fy) { return RowPlane{plane.origin + plane.dy * fy, plane.dx}; }

/// Gouraud and flat: colour = base * D + S with D, S the interpolated light (channels 0-5) and
/// base the material's colour, times the pattern's texel at (u, v) (channels 6, 7) when
/// `kPatterned`. Perspective-correct: each channel is (channel / w) / (1 / w).
template <bool kPatterned>
struct SpanShader {
  static constexpr int kChannels = kPatterned ? 8 : 6;

  SpanShader(const TriangleSetup& t, const Material& material, const Texture& texture, float fy)
      : inverse_w(AlongRow(t.inverse_w, fy)),
        base{material.colour[0], material.colour[1], material.colour[2]},
        pattern(texture) {
    for (int k = 0; k < kChannels; ++k) channel[k] = AlongRow(t.channels[k], fy);
  }

  /// The colour at fx pixels from the box's first column, 0..1 (more under strong light).
  void At(float fx, float* r, float* g, float* b) const {
    const float w = 1.0f / (inverse_w.at + inverse_w.step * fx);
    float c[kChannels];
    for (int k = 0; k < kChannels; ++k) c[k] = (channel[k].at + channel[k].step * fx) * w;
    float red = base[0], green = base[1], blue = base[2];
    if constexpr (kPatterned) {
      const uint8_t* texel = pattern.Sample(c[6], c[7]);
      red *= texel[0] * (1.0f / 255);
      green *= texel[1] * (1.0f / 255);
      blue *= texel[2] * (1.0f / 255);
    }
    *r = red * c[0] + c[3];
    *g = green * c[1] + c[4];
    *b = blue * c[2] + c[5];
  }

  RowPlane inverse_w;
  RowPlane channel[kChannels];
  float base[3];
  const Texture& pattern;
};

/// Short spans (the flag's small triangles) and patterned ones (whose texel fetch does not
/// vectorise): one pass, shading only the pixels in front. depth and rgb point at pixel `first`.
template <bool kPatterned>
void FillSpanOnePass(const SpanShader<kPatterned>& shader, const RowPlane& z, float fx0, int n, float* depth,
                     uint8_t* rgb) {
  for (int i = 0; i < n; ++i, rgb += 3) {
    const float fx = fx0 + float(i);
    const float here = z.at + z.step * fx;
    if (!(here < depth[i])) continue;
    depth[i] = here;
    float r, g, b;
    shader.At(fx, &r, &g, &b);
    rgb[0] = ToByte(r);
    rgb[1] = ToByte(g);
    rgb[2] = ToByte(b);
  }
}

/// Long plain spans (the ground, the pole): three passes, the first two free of branches so
/// that they vectorise: the depth test (keeping a mask), the colours of every pixel, then the
/// stores where the mask is set. depth and rgb point at pixel `first`.
void FillSpanThreePasses(const SpanShader<false>& shader, const RowPlane& z, float fx0, int n,
                         float* __restrict depth, uint8_t* __restrict rgb) {
  constexpr int kMaxSpan = 4096;
  alignas(32) uint8_t visible[kMaxSpan];
  alignas(32) uint8_t red[kMaxSpan], green[kMaxSpan], blue[kMaxSpan];
  int in_front = 0;
  for (int i = 0; i < n; ++i) {
    const float here = z.at + z.step * (fx0 + float(i));
    const bool nearer = here < depth[i];
    depth[i] = nearer ? here : depth[i];
    visible[i] = nearer;
    in_front += nearer;
  }
  if (in_front == 0) return;
  for (int i = 0; i < n; ++i) {
    float r, g, b;
    shader.At(fx0 + float(i), &r, &g, &b);
    red[i] = ToByte(r);
    green[i] = ToByte(g);
    blue[i] = ToByte(b);
  }
  for (int i = 0; i < n; ++i, rgb += 3) {
    if (in_front < n && !visible[i]) continue;
    rgb[0] = red[i];
    rgb[1] = green[i];
    rgb[2] = blue[i];
  }
}

template <bool kPatterned>
void FillSpanInterpolated(const TriangleSetup& t, const Material& material, const Texture& pattern, float fy,
                          int first, int last, float* depth, uint8_t* rgb) {
  constexpr int kLongSpan = 16;  ///< px: below this the passes' set-up costs more than they save
  const SpanShader<kPatterned> shader(t, material, pattern, fy);
  const RowPlane z = AlongRow(t.depth, fy);
  const int n = last - first + 1;
  const float fx0 = float(first - t.min_x);
  if constexpr (!kPatterned) {
    if (n >= kLongSpan) return FillSpanThreePasses(shader, z, fx0, n, depth, rgb);
  }
  FillSpanOnePass(shader, z, fx0, n, depth, rgb);
}

/// Phong: channels are world position (0-2) and normal (3-5); Blinn-Phong per pixel.
/// depth and rgb point at pixel `first`.
void FillSpanPhong(const TriangleSetup& t, const ShadeContext& context, float fy, int first, int last,
                   float* depth, uint8_t* rgb) {
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
    uint8_t* pixel = rgb + 3 * (x - first);
    pixel[0] = ToByte(colour[0]);
    pixel[1] = ToByte(colour[1]);
    pixel[2] = ToByte(colour[2]);
  }
}

}  // namespace

void ClearTile(const RenderScene& scene, const TileTarget& target) {
  const TileRect& tile = target.rect;
  const int pixels = tile.x1 - tile.x0;
  for (int y = tile.y0; y < tile.y1; ++y) {
    const float t = target.image_height > 1 ? float(y) / (target.image_height - 1) : 0.0f;
    const Eigen::Vector3f sky = scene.sky_top + t * (scene.sky_horizon - scene.sky_top);
    // Four pixels are 12 bytes: copy that block along the row, then the last few pixels.
    uint8_t block[12];
    for (int k = 0; k < 12; ++k) block[k] = ToByte(sky[k % 3]);
    uint8_t* row = target.Pixel(tile.x0, y);
    int x = 0;
    for (; x + 4 <= pixels; x += 4) std::memcpy(row + 3 * x, block, sizeof(block));
    for (; x < pixels; ++x) std::memcpy(row + 3 * x, block, 3);
    std::fill_n(target.Depth(tile.x0, y), pixels, 1.0f);
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
    uint8_t* rgb = target.Pixel(first, y);
    if (context.mode == ShadingMode::kPhong) {
      FillSpanPhong(t, context, fy, first, last, depth, rgb);
    } else if (material.patterned) {
      FillSpanInterpolated<true>(t, material, context.scene->pattern, fy, first, last, depth, rgb);
    } else {
      FillSpanInterpolated<false>(t, material, context.scene->pattern, fy, first, last, depth, rgb);
    }
  }
}

}  // namespace flagsim::render
