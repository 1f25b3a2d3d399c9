#include "server/render/tile_raster.hpp"

#include <algorithm>
#include <cstring>

#if defined(__AVX2__)
#include <immintrin.h>
#endif

namespace flagsim::render {
namespace {

/// 0..1 => 0..255, rounded and clamped; branch-free so that the loops using it vectorise.
/// Clamped above before the conversion to int and below after it, which is min(max(v, 0), 255)
/// converted, in fewer vector instructions.
uint32_t ToByte(float value) {
  const int32_t truncated = static_cast<int32_t>(std::min(value * 255.0f + 0.5f, 255.0f));
  return static_cast<uint32_t>(std::max(truncated, 0));
}

/// A triangle's planes side by side: depth, 1 / w, the channels, then zeros up to whole
/// vectors. A row's values of them all are then a few vector operations.
struct Planes {
  static constexpr int kDepth = 0, kInverseW = 1, kChannel = 2;
  static constexpr int kCount = 16;
  static_assert(kChannel + kPlaneChannels <= kCount);

  explicit Planes(const TriangleSetup& t) {
    const auto put = [this](int k, const Plane& plane) {
      origin[k] = plane.origin;
      dx[k] = plane.dx;
      dy[k] = plane.dy;
    };
    put(kDepth, t.depth);
    put(kInverseW, t.inverse_w);
    for (int k = 0; k < kPlaneChannels; ++k) put(kChannel + k, t.channels[k]);
  }

  /// Every plane along row fy: at[k] + dx[k] * fx at fx pixels from the box's first column.
  void AlongRow(float fy, float at[kCount]) const {
#pragma omp simd
    for (int k = 0; k < kCount; ++k) at[k] = origin[k] + dy[k] * fy;
  }

  alignas(32) float origin[kCount] = {};
  alignas(32) float dx[kCount] = {};
  alignas(32) float dy[kCount] = {};
};

/// Gouraud and flat: colour = base * D + S with D, S the interpolated light (channels 0-5) and
/// base the material's colour, times the pattern filtered at (u, v) (channels 6, 7) and the
/// triangle's level of detail when `kPatterned` (texture_filter.hpp). Perspective-correct: each channel is (channel / w) / (1 / w). Shades a block
/// of kSpanLanes pixels at once.
template <bool kPatterned>
class BlockShader {
 public:
  static constexpr int kChannels = kPatterned ? 8 : 6;

  /// `pattern` is read only when kPatterned, at level of detail `lod`.
  BlockShader(const Planes& planes, const Material& material, const FilteredTexture* pattern, float lod = 0)
      : planes_(planes), base_{material.colour[0], material.colour[1], material.colour[2]} {
    if constexpr (kPatterned) sampler_ = pattern->SamplerAt(lod);
  }

  /// The colours at fx[i] pixels from the box's first column on rows where plane k is at(k, i)
  /// in that column. One loop over the lanes, so that each step's values stay in vector
  /// registers; the loops inside it are unrolled, which vectorising it needs.
  template <class At>
  void Shade(const At& at, const float fx[kSpanLanes], uint32_t colour[kSpanLanes]) const {
    const float* step = planes_.dx;
#pragma omp simd
    for (int i = 0; i < kSpanLanes; ++i) {
      const float w = 1.0f / (at(Planes::kInverseW, i) + step[Planes::kInverseW] * fx[i]);
      float c[kChannels];
#pragma GCC unroll 8
      for (int k = 0; k < kChannels; ++k) {
        c[k] = (at(Planes::kChannel + k, i) + step[Planes::kChannel + k] * fx[i]) * w;
      }
      float base[3] = {base_[0], base_[1], base_[2]};
      if constexpr (kPatterned) {
        float texel[3];
        sampler_.Sample(c[6], c[7], texel);
#pragma GCC unroll 3
        for (int j = 0; j < 3; ++j) base[j] *= texel[j];
      }
      colour[i] = PackRgbx(ToByte(base[0] * c[0] + c[3]), ToByte(base[1] * c[1] + c[4]),
                           ToByte(base[2] * c[2] + c[5]));
    }
  }

 private:
  const Planes& planes_;
  float base_[3];
  FilteredTexture::Sampler sampler_;  ///< kPatterned: the triangle's levels
};

/// The n pixels of a row from fx0 pixels past the box's first column, kSpanLanes at a time:
/// the depth test, then where any pixel of the block is in front, the block's colours stored
/// to those pixels. Lanes past the span repeat its last pixel and are masked off. `at` holds
/// the planes along the row; depth and rgbx point at the span's first pixel.
template <bool kPatterned>
void FillSpan(const BlockShader<kPatterned>& shader, const Planes& planes, const float at[Planes::kCount],
              float fx0, int n, float* depth, uint32_t* rgbx) {
  const float z_at = at[Planes::kDepth], z_step = planes.dx[Planes::kDepth];
  for (int start = 0; start < n; start += kSpanLanes, depth += kSpanLanes, rgbx += kSpanLanes) {
    float fx[kSpanLanes];
    int32_t in_front[kSpanLanes];
    int any = 0;
#pragma omp simd reduction(| : any)
    for (int i = 0; i < kSpanLanes; ++i) {
      fx[i] = fx0 + float(std::min(start + i, n - 1));
      const float here = z_at + z_step * fx[i];
      const bool nearer = start + i < n && here < depth[i];
      depth[i] = nearer ? here : depth[i];
      in_front[i] = nearer;
      any |= nearer;
    }
    if (!any) continue;
    uint32_t colour[kSpanLanes];
    shader.Shade([at](int k, int) { return at[k]; }, fx, colour);
#pragma omp simd
    for (int i = 0; i < kSpanLanes; ++i) rgbx[i] = in_front[i] ? colour[i] : rgbx[i];
  }
}

/// A narrow triangle's pixels, kSpanLanes at a time whatever their rows, so that a triangle a
/// few pixels across takes a block or two rather than a block a row. Each lane holds its
/// pixel's place in the tile and its distance from the box's first column and row; plane k on
/// the lane's row is origin + dy * fy, as along a row. The depth test and the stores go pixel
/// by pixel; no pixel is in a block twice.
template <bool kPatterned>
class PixelBlocks {
 public:
  PixelBlocks(const BlockShader<kPatterned>& shader, const Planes& planes, const TriangleSetup& t,
              const TileTarget& target)
      : shader_(shader), planes_(planes), t_(t), target_(target) {}

  /// Pixels first .. last of row y into the block, which is shaded whenever it is full.
  void AddSpan(int y, int first, int last) {
    const int32_t row = int32_t(size_t(y - target_.rect.y0) * target_.stride) - target_.rect.x0;
    const int32_t row_from_box = y - t_.min_y;
    for (int x = first; x <= last; ++x) {
      offset_[count_] = row + x;
      column_[count_] = x - t_.min_x;
      row_[count_] = row_from_box;
      if (++count_ == kSpanLanes) Flush();
    }
  }

  /// Shades the pixels added since the last full block; lanes past them repeat the last one
  /// and are masked off.
  void Flush() {
    const int count = count_;
    if (count == 0) return;
    count_ = 0;
    for (int i = count; i < kSpanLanes; ++i) {
      offset_[i] = offset_[count - 1];
      column_[i] = column_[count - 1];
      row_[i] = row_[count - 1];
    }
    float fx[kSpanLanes], fy[kSpanLanes], there[kSpanLanes];
    for (int i = 0; i < kSpanLanes; ++i) {
      fx[i] = float(column_[i]);
      fy[i] = float(row_[i]);
      there[i] = target_.depth[offset_[i]];
    }
    const float* origin = planes_.origin;
    const float* dy = planes_.dy;
    const auto at = [origin, dy, &fy](int k, int i) { return origin[k] + dy[k] * fy[i]; };
    const float z_step = planes_.dx[Planes::kDepth];
    float here[kSpanLanes];
    int32_t in_front[kSpanLanes];
    int any = 0;
#pragma omp simd reduction(| : any)
    for (int i = 0; i < kSpanLanes; ++i) {
      here[i] = at(Planes::kDepth, i) + z_step * fx[i];
      in_front[i] = i < count && here[i] < there[i];
      any |= in_front[i];
    }
    if (!any) return;
    uint32_t colour[kSpanLanes];
    shader_.Shade(at, fx, colour);
    for (int i = 0; i < count; ++i) {
      if (!in_front[i]) continue;
      target_.depth[offset_[i]] = here[i];
      target_.rgbx[offset_[i]] = colour[i];
    }
  }

 private:
  const BlockShader<kPatterned>& shader_;
  const Planes& planes_;
  const TriangleSetup& t_;
  const TileTarget& target_;
  int count_ = 0;
  int32_t offset_[kSpanLanes];  ///< from the tile's first pixel, in both its colour and depth
  int32_t column_[kSpanLanes];  ///< from the box's first column
  int32_t row_[kSpanLanes];     ///< from the box's first row
};

/// n RGBX words => n RGB pixels. With AVX2, 8 pixels at a time: in each 16-byte half the
/// R, G, B bytes of its 4 pixels go to the front, then the two 12-byte runs side by side. All
/// 32 bytes are stored while 3 more pixels follow (the next 8 write the last 8 bytes again);
/// the row's last pixels are stored as exactly 24 bytes, the very last 8 from n - 8 (which may
/// write pixels again, with the same bytes), so nothing is written past the row.
void RgbxToRgb(const uint32_t* rgbx, int n, uint8_t* rgb) {
  int i = 0;
#if defined(__AVX2__)
  const __m256i pack = _mm256_setr_epi8(0, 1, 2, 4, 5, 6, 8, 9, 10, 12, 13, 14, -1, -1, -1, -1,  //
                                        0, 1, 2, 4, 5, 6, 8, 9, 10, 12, 13, 14, -1, -1, -1, -1);
  const __m256i join = _mm256_setr_epi32(0, 1, 2, 4, 5, 6, 3, 7);
  const auto packed = [&](int first) {
    const __m256i eight = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(rgbx + first));
    return _mm256_permutevar8x32_epi32(_mm256_shuffle_epi8(eight, pack), join);
  };
  const auto store_24 = [&](int first) {
    const __m256i bytes = packed(first);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(rgb + 3 * first), _mm256_castsi256_si128(bytes));
    _mm_storel_epi64(reinterpret_cast<__m128i*>(rgb + 3 * first + 16), _mm256_extracti128_si256(bytes, 1));
  };
  for (; n - i >= 11; i += 8) _mm256_storeu_si256(reinterpret_cast<__m256i*>(rgb + 3 * i), packed(i));
  for (; n - i > 8; i += 8) store_24(i);
  if (n >= 8 && i < n) {
    store_24(n - 8);
    i = n;
  }
#endif
  for (; i < n; ++i) std::memcpy(rgb + 3 * i, rgbx + i, 3);
}

/// Phong: channels are world position (0-2) and normal (3-5); Blinn-Phong per pixel, for the
/// n pixels of a row from fx0 pixels past the box's first column. `at` holds the planes along
/// the row; depth and rgbx point at the span's first pixel.
void FillSpanPhong(const TriangleSetup& t, const ShadeContext& context, const Planes& planes,
                   const float at[Planes::kCount], float fx0, int n, float* depth, uint32_t* rgbx) {
  const RenderScene& scene = *context.scene;
  const Material& material = scene.materials[t.material];
  const auto value = [&](int k, float fx) { return at[k] + planes.dx[k] * fx; };
  for (int i = 0; i < n; ++i) {
    const float fx = fx0 + float(i);
    const float depth_here = value(Planes::kDepth, fx);
    if (!(depth_here < depth[i])) continue;
    depth[i] = depth_here;
    const float w = 1.0f / value(Planes::kInverseW, fx);
    float c[kPlaneChannels];
    for (int k = 0; k < kPlaneChannels; ++k) c[k] = value(Planes::kChannel + k, fx) * w;
    Eigen::Vector3f normal = Eigen::Vector3f(c[3], c[4], c[5]).normalized();
    if (t.back_facing) normal = -normal;
    const Shade shade =
        ShadePoint(material, scene.lighting, Eigen::Vector3f(c[0], c[1], c[2]), normal, context.eye);
    Eigen::Vector3f base = material.colour;
    if (material.patterned) {
      float texel[3];
      context.pattern->Sample(c[6], c[7], context.pattern->LevelOfDetail(t.uv_area_per_pixel), texel);
      base = base.cwiseProduct(Eigen::Vector3f(texel[0], texel[1], texel[2]));
    }
    const Eigen::Vector3f colour = base.cwiseProduct(shade.diffuse) + shade.specular;
    rgbx[i] = PackRgbx(ToByte(colour[0]), ToByte(colour[1]), ToByte(colour[2]));
  }
}

/// Every pixel of columns first .. last, row after row.
class BoxSpans {
 public:
  BoxSpans(int first, int last) : first_(first), last_(last) {}
  bool Span(int* first, int* last) const {
    *first = first_;
    *last = last_;
    return true;
  }
  void NextRow() {}

 private:
  int first_, last_;
};

/// Rows y_first .. y_last of a triangle in the tile, each row's pixels given by `spans` (RowSpans
/// LaneSpans or BoxSpans, positioned at y_first) and drawn by fill_span(y, first, last).
template <class Spans, class FillSpanAt>
void FillRows(const TileTarget& target, int y_first, int y_last, Spans spans, const FillSpanAt& fill_span) {
  for (int y = y_first; y <= y_last; ++y, spans.NextRow()) {
    int first = 0, last = 0;
    if (!spans.Span(&first, &last)) continue;
    first = std::max(first, target.rect.x0);
    last = std::min(last, target.rect.x1 - 1);
    if (first <= last) fill_span(y, first, last);
  }
}

}  // namespace

TileBuffer::TileBuffer(int size)
    : stride_(size_t(size) + kSpanLanes - 1),
      rgbx_(stride_ * size, PackRgbx(0, 0, 0)),
      depth_(stride_ * size, 1.0f) {}

TileTarget TileBuffer::Target(const TileRect& rect) {
  TileTarget target;
  target.rect = rect;
  target.rgbx = rgbx_.data();
  target.depth = depth_.data();
  target.stride = stride_;
  return target;
}

void CopyOut(const TileTarget& target, bool keep_depth, Framebuffer* framebuffer) {
  const TileRect& tile = target.rect;
  const int pixels = tile.x1 - tile.x0;
  for (int y = tile.y0; y < tile.y1; ++y) {
    RgbxToRgb(target.Rgbx(tile.x0, y), pixels, framebuffer->Pixel(tile.x0, y));
    if (keep_depth) {
      std::memcpy(&framebuffer->depth[size_t(y) * framebuffer->width + tile.x0], target.Depth(tile.x0, y),
                  size_t(pixels) * sizeof(float));
    }
  }
}

void CopyIn(const Framebuffer& framebuffer, const TileTarget& target) {
  const TileRect& tile = target.rect;
  for (int y = tile.y0; y < tile.y1; ++y) {
    const uint8_t* rgb = &framebuffer.rgb[(size_t(y) * framebuffer.width + tile.x0) * 3];
    uint32_t* rgbx = target.Rgbx(tile.x0, y);
    for (int x = 0; x < tile.x1 - tile.x0; ++x)
      rgbx[x] = PackRgbx(rgb[3 * x], rgb[3 * x + 1], rgb[3 * x + 2]);
    std::memcpy(target.Depth(tile.x0, y), &framebuffer.depth[size_t(y) * framebuffer.width + tile.x0],
                size_t(tile.x1 - tile.x0) * sizeof(float));
  }
}

void SkyRows(const RenderScene& scene, int height, std::vector<uint32_t>* rows) {
  rows->resize(size_t(height));
  for (int y = 0; y < height; ++y) {
    const float t = height > 1 ? float(y) / (height - 1) : 0.0f;
    const Eigen::Vector3f sky = scene.sky_top + t * (scene.sky_horizon - scene.sky_top);
    (*rows)[y] = PackRgbx(ToByte(sky[0]), ToByte(sky[1]), ToByte(sky[2]));
  }
}

void ClearTile(const uint32_t* sky_rows, const TileTarget& target) {
  // Whole blocks of kSpanLanes pixels, the last reaching into the row's room past x1.
  const TileRect& tile = target.rect;
  const int pixels = tile.x1 - tile.x0;
  for (int y = tile.y0; y < tile.y1; ++y) {
    const uint32_t colour = sky_rows[y];
    uint32_t* rgbx = target.Rgbx(tile.x0, y);
    float* depth = target.Depth(tile.x0, y);
    for (int start = 0; start < pixels; start += kSpanLanes) {
#pragma omp simd
      for (int i = start; i < start + kSpanLanes; ++i) {
        rgbx[i] = colour;
        depth[i] = 1.0f;
      }
    }
  }
}

void RasterizeTriangle(const TriangleSetup& t, const ShadeContext& context, const TileTarget& target) {
  const TileRect& tile = target.rect;
  const int y_first = std::max(t.min_y, tile.y0), y_last = std::min(t.max_y, tile.y1 - 1);
  const int x_first = std::max(t.min_x, tile.x0), x_last = std::min(t.max_x, tile.x1 - 1);
  if (y_first > y_last || x_first > x_last) return;
  // Narrow triangles are walked in a window; larger ones are first tested against the box,
  // which skips the rows of boxes they miss or cover whole.
  const bool in_window = t.narrow && x_last - x_first < LaneSpans::kWidth;
  const BoxCover cover = in_window ? BoxCover::kPart : CoverOfBox(t, x_first, y_first, x_last, y_last);
  if (cover == BoxCover::kNone) return;
  const Planes planes(t);
  // fill(at, fx0, n, depth, rgbx) draws n pixels of a row: each row's planes and pixels for it.
  const auto fill_rows = [&](const auto& fill) {
    const auto fill_span = [&](int y, int first, int last) {
      alignas(32) float at[Planes::kCount];
      planes.AlongRow(float(y - t.min_y), at);
      fill(at, float(first - t.min_x), last - first + 1, target.Depth(first, y), target.Rgbx(first, y));
    };
    if (in_window) {
      FillRows(target, y_first, y_last, LaneSpans(t, x_first, x_last, y_first), fill_span);
    } else if (cover == BoxCover::kAll) {
      FillRows(target, y_first, y_last, BoxSpans(x_first, x_last), fill_span);
    } else {
      FillRows(target, y_first, y_last, RowSpans(t, y_first), fill_span);
    }
  };
  // Narrow triangles' pixels in blocks of any rows; the others' a row at a time.
  const auto fill = [&](const auto& shader) {
    if (in_window) {
      PixelBlocks blocks(shader, planes, t, target);
      FillRows(target, y_first, y_last, LaneSpans(t, x_first, x_last, y_first),
               [&](int y, int first, int last) { blocks.AddSpan(y, first, last); });
      blocks.Flush();
    } else {
      fill_rows([&](const float* at, float fx0, int n, float* depth, uint32_t* rgbx) {
        FillSpan(shader, planes, at, fx0, n, depth, rgbx);
      });
    }
  };
  const Material& material = context.scene->materials[t.material];
  if (context.mode == ShadingMode::kPhong) {
    fill_rows([&](const float* at, float fx0, int n, float* depth, uint32_t* rgbx) {
      FillSpanPhong(t, context, planes, at, fx0, n, depth, rgbx);
    });
  } else if (material.patterned) {
    fill(BlockShader<true>(planes, material, context.pattern, context.pattern->LevelOfDetail(t.uv_area_per_pixel)));
  } else {
    fill(BlockShader<false>(planes, material, context.pattern));
  }
}

}  // namespace flagsim::render
