#include "server/render/tile_raster.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>

#if defined(__AVX2__)
#include <immintrin.h>
#endif

#include "server/render/multisample_raster.hpp"
#include "server/render/span_shader.hpp"
#include "server/render/srgb.hpp"

namespace flagsim::render {
namespace {

/// A display colour 0..1 (the sky's, sRGB already) => 0..255, rounded and clamped.
uint32_t ToByte(float value) { return uint32_t(std::clamp(value * 255.0f + 0.5f, 0.0f, 255.0f)); }

/// The n pixels of a row from fx0 pixels past the box's first column, kSpanLanes at a time:
/// the depth test, then where any pixel of the block is in front, the block's colours stored
/// to those pixels. Lanes past the span repeat its last pixel and are masked off. `at` holds
/// the planes along the row; depth and rgbx point at the span's first pixel.
template <class Shader>
void FillSpan(const Shader& shader, const Planes& planes, const float at[Planes::kCount], float fx0, int n,
              float* depth, uint32_t* rgbx) {
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

/// FillSpan for a surface cut by its pattern's alpha (Shader::cutout()): each block is shaded
/// first, and a pixel is drawn where its alpha is at least 1/2 and it is in front. (With more
/// than one sample, alpha chooses how many samples it covers: multisample_raster.cpp.)
template <class Shader>
void FillSpanCutout(const Shader& shader, const Planes& planes, const float at[Planes::kCount], float fx0,
                    int n, float* depth, uint32_t* rgbx) {
  const float z_at = at[Planes::kDepth], z_step = planes.dx[Planes::kDepth];
  for (int start = 0; start < n; start += kSpanLanes, depth += kSpanLanes, rgbx += kSpanLanes) {
    float fx[kSpanLanes], alpha[kSpanLanes];
    for (int i = 0; i < kSpanLanes; ++i) fx[i] = fx0 + float(std::min(start + i, n - 1));
    uint32_t colour[kSpanLanes];
    shader.Shade([at](int k, int) { return at[k]; }, fx, colour, alpha);
    for (int i = 0; i < std::min(kSpanLanes, n - start); ++i) {
      const float here = z_at + z_step * fx[i];
      if (!(alpha[i] >= 0.5f && here < depth[i])) continue;
      depth[i] = here;
      rgbx[i] = colour[i];
    }
  }
}

/// A narrow triangle's pixels, kSpanLanes at a time whatever their rows, so that a triangle a
/// few pixels across takes a block or two rather than a block a row. Each lane holds its
/// pixel's place in the tile and its distance from the box's first column and row; plane k on
/// the lane's row is origin + dy * fy, as along a row. The depth test and the stores go pixel
/// by pixel; no pixel is in a block twice.
template <class Shader>
class PixelBlocks {
 public:
  PixelBlocks(const Shader& shader, const Planes& planes, const TriangleSetup& t, const TileTarget& target)
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
  const Shader& shader_;
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

/// Phong, for the n pixels of a row from fx0 pixels past the box's first column, each shaded
/// only where it passes the depth test. `at` holds the planes along the row; depth and rgbx
/// point at the span's first pixel.
void FillSpanPhong(const PhongShader& shader, const Planes& planes, const float at[Planes::kCount], float fx0,
                   int n, float* depth, uint32_t* rgbx) {
  for (int i = 0; i < n; ++i) {
    const float fx = fx0 + float(i);
    const float depth_here = at[Planes::kDepth] + planes.dx[Planes::kDepth] * fx;
    if (!(depth_here < depth[i])) continue;
    float alpha = 1;  // set by a pattern that cuts the surface
    const uint32_t colour = shader.ShadePixel([at](int k) { return at[k]; }, fx, &alpha);
    if (alpha < 0.5f) continue;
    depth[i] = depth_here;
    rgbx[i] = colour;
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

/// The mean of kSamples pixels `plane` words apart, for n pixels of a row, in light: each
/// sample's sRGB bytes decoded to 16-bit linear, summed, divided (rounded) and encoded again.
/// A pixel whose samples agree keeps its bytes (srgb.hpp's tables round-trip every byte), so
/// blocks of kSpanLanes pixels whose samples all agree (inside triangles, the sky) are copied
/// without the tables. The row has room for a block past n (kSpanLanes).
template <int kSamples>
void ResolveRow(const uint32_t* rgbx, size_t plane, int n, uint32_t* out) {
  static_assert((kSamples & (kSamples - 1)) == 0, "a power of two");
  constexpr int kShift = __builtin_ctz(unsigned(kSamples));
  const uint32_t* decode = kSrgbDecode.data();
  for (int start = 0; start < n; start += kSpanLanes) {
    const uint32_t* first = rgbx + start;
    int differ = 0;
#pragma omp simd reduction(| : differ)
    for (int i = 0; i < kSpanLanes; ++i) {
      for (int k = 1; k < kSamples; ++k) differ |= first[plane * size_t(k) + size_t(i)] != first[i];
    }
    if (!differ) {
      for (int i = 0; i < kSpanLanes; ++i) out[start + i] = first[i];
      continue;
    }
#pragma omp simd
    for (int i = 0; i < kSpanLanes; ++i) {
      uint32_t sum[3] = {0, 0, 0};
#pragma GCC unroll 8
      for (int k = 0; k < kSamples; ++k) {
        const uint32_t word = first[plane * size_t(k) + size_t(i)];
#pragma GCC unroll 3
        for (int c = 0; c < 3; ++c) sum[c] += decode[(word >> (8 * c)) & 0xffu];
      }
      uint32_t bytes[3];
#pragma GCC unroll 3
      for (int c = 0; c < 3; ++c) bytes[c] = EncodeSrgb16((sum[c] + kSamples / 2) >> kShift);
      out[start + i] = PackRgbx(bytes[0], bytes[1], bytes[2]);
    }
  }
}

/// ResolveRow for the target's sample count.
void Resolve(const TileTarget& target, const uint32_t* rgbx, int n, uint32_t* out) {
  switch (target.samples) {
    case 2:
      return ResolveRow<2>(rgbx, target.plane, n, out);
    case 4:
      return ResolveRow<4>(rgbx, target.plane, n, out);
    case 8:
      return ResolveRow<8>(rgbx, target.plane, n, out);
  }
  std::abort();  // SamplePattern has 1, 2, 4 or 8 samples
}

}  // namespace

TileBuffer::TileBuffer(int size, int samples)
    : stride_(size_t(size) + kSpanLanes - 1),
      plane_(stride_ * size_t(size)),
      samples_(samples),
      rgbx_(plane_ * size_t(samples), PackRgbx(0, 0, 0)),
      depth_(plane_ * size_t(samples), 1.0f),
      row_mask_(stride_),
      row_colour_(stride_) {}

TileTarget TileBuffer::Target(const TileRect& rect) {
  TileTarget target;
  target.rect = rect;
  target.rgbx = rgbx_.data();
  target.depth = depth_.data();
  target.stride = stride_;
  target.samples = samples_;
  target.plane = plane_;
  target.row_mask = row_mask_.data();
  target.row_colour = row_colour_.data();
  return target;
}

void SampleImage::Resize(int new_width, int new_height, int new_samples) {
  width = new_width;
  height = new_height;
  samples = new_samples;
  rgbx.resize(size_t(width) * height * samples);
  depth.resize(size_t(width) * height * samples);
}

void CopyOut(const TileTarget& target, bool keep_depth, Framebuffer* framebuffer) {
  const TileRect& tile = target.rect;
  const int pixels = tile.x1 - tile.x0;
  for (int y = tile.y0; y < tile.y1; ++y) {
    const uint32_t* row = target.Rgbx(tile.x0, y);
    if (target.samples > 1) {
      Resolve(target, row, pixels, target.row_colour);
      row = target.row_colour;
    }
    RgbxToRgb(row, pixels, framebuffer->Pixel(tile.x0, y));
    if (!keep_depth) continue;
    float* depth = &framebuffer->depth[size_t(y) * framebuffer->width + tile.x0];
    std::memcpy(depth, target.Depth(tile.x0, y), size_t(pixels) * sizeof(float));
    for (int k = 1; k < target.samples; ++k) {
      const float* sample = target.Depth(tile.x0, y, k);
      for (int x = 0; x < pixels; ++x) depth[x] = std::min(depth[x], sample[x]);
    }
  }
}

namespace {

/// Calls copy(tile's row, image's row, pixels) for every sample's every row of the tile.
template <class TileWord, class ImageWord, class Copy>
void ForTileRows(const TileTarget& target, int image_width, int image_height, TileWord* tile_plane,
                 ImageWord* image_plane, Copy copy) {
  const TileRect& tile = target.rect;
  const size_t image_plane_size = size_t(image_width) * image_height;
  for (int k = 0; k < target.samples; ++k) {
    for (int y = tile.y0; y < tile.y1; ++y) {
      copy(tile_plane + target.plane * k + size_t(y - tile.y0) * target.stride,
           image_plane + image_plane_size * k + size_t(y) * image_width + tile.x0, size_t(tile.x1 - tile.x0));
    }
  }
}

}  // namespace

void SaveTile(const TileTarget& target, SampleImage* image) {
  const auto save = [](const auto* tile_row, auto* image_row, size_t n) {
    std::memcpy(image_row, tile_row, n * sizeof(*tile_row));
  };
  ForTileRows(target, image->width, image->height, target.rgbx, image->rgbx.data(), save);
  ForTileRows(target, image->width, image->height, target.depth, image->depth.data(), save);
}

void LoadTile(const SampleImage& image, const TileTarget& target) {
  const auto load = [](auto* tile_row, const auto* image_row, size_t n) {
    std::memcpy(tile_row, image_row, n * sizeof(*tile_row));
  };
  ForTileRows(target, image.width, image.height, target.rgbx, image.rgbx.data(), load);
  ForTileRows(target, image.width, image.height, target.depth, image.depth.data(), load);
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
  for (int k = 0; k < target.samples; ++k) {
    for (int y = tile.y0; y < tile.y1; ++y) {
      const uint32_t colour = sky_rows[y];
      uint32_t* rgbx = target.Rgbx(tile.x0, y, k);
      float* depth = target.Depth(tile.x0, y, k);
      for (int start = 0; start < pixels; start += kSpanLanes) {
#pragma omp simd
        for (int i = start; i < start + kSpanLanes; ++i) {
          rgbx[i] = colour;
          depth[i] = 1.0f;
        }
      }
    }
  }
}

void RasterizeTriangle(const TriangleSetup& t, const ShadeContext& context, const TileTarget& target) {
  if (target.samples > 1) {
    RasterizeMultisampled(t, context, target);
    return;
  }
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
    if (shader.cutout()) {
      fill_rows([&](const float* at, float fx0, int n, float* depth, uint32_t* rgbx) {
        FillSpanCutout(shader, planes, at, fx0, n, depth, rgbx);
      });
    } else if (in_window) {
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
  if (context.mode == ShadingMode::kPhong) {  // shaded pixel by pixel, only where in front
    const PhongShader shader(t, context, planes);
    fill_rows([&](const float* at, float fx0, int n, float* depth, uint32_t* rgbx) {
      FillSpanPhong(shader, planes, at, fx0, n, depth, rgbx);
    });
  } else {
    WithShader(t, context, planes, x_first, y_first, x_last, y_last, fill);
  }
}

}  // namespace flagsim::render
