#include "server/render/multisample_raster.hpp"

#include <algorithm>
#include <climits>
#include <cstring>

#include "server/render/span_shader.hpp"

namespace flagsim::render {
namespace {

/// One sample's part of a row: covered pixels [first, last] (empty when first > last).
struct SampleSpan {
  int first = 0, last = -1;
};

/// Plane k at lane i for the shaders: `at` along the row, moved fy[i] px down.
class AtRowOffsets {
 public:
  AtRowOffsets(const float* at, const Planes& planes, const float* fy) : at_(at), dy_(planes.dy), fy_(fy) {}
  float operator()(int k, int i) const { return at_[k] + dy_[k] * fy_[i]; }

 private:
  const float* at_;
  const float* dy_;
  const float* fy_;
};

/// The rows y_first .. y_last of a triangle whose box in the tile is columns x_first .. x_last.
/// `whole`: every sample of the box is inside (CoverOfBox's kAll), so no edge is walked.
class MultisampledRows {
 public:
  MultisampledRows(const TriangleSetup& t, const Planes& planes, const SamplePattern& pattern,
                   const TileTarget& target, int x_first, int x_last)
      : t_(t), planes_(planes), pattern_(pattern), target_(target), x_first_(x_first), x_last_(x_last) {
    // A sample's depth sits off the pixel centre's by the plane's slope times its offset.
    for (int k = 0; k < pattern.count; ++k) {
      depth_offset_[k] = planes.dx[Planes::kDepth] * float(pattern.offsets[k].x) / kSubpixels +
                         planes.dy[Planes::kDepth] * float(pattern.offsets[k].y) / kSubpixels;
    }
  }

  template <class Shader>
  void Fill(const Shader& shader, int y_first, int y_last, bool whole) {
    RowSpans spans[kMaxSamples];
    if (!whole) {
      for (int k = 0; k < pattern_.count; ++k) spans[k] = RowSpans(t_, y_first, pattern_.offsets[k]);
    }
    for (int y = y_first; y <= y_last; ++y) {
      SampleSpan row[kMaxSamples];
      for (int k = 0; k < pattern_.count; ++k) {
        if (whole) {
          row[k] = {x_first_, x_last_};
          continue;
        }
        if (spans[k].Span(&row[k].first, &row[k].last)) {
          row[k].first = std::max(row[k].first, x_first_);
          row[k].last = std::min(row[k].last, x_last_);
        } else {
          row[k] = {};
        }
        spans[k].NextRow();
      }
      FillRow(shader, y, row);
    }
  }

  /// A narrow triangle, in a window of LaneSamples::kWidth columns from x_first: each row's
  /// coverage as bits per lane, then the same three steps on the window's lanes at once.
  template <class Shader>
  void FillNarrow(const Shader& shader, int y_first, int y_last) {
    constexpr int kLanes = LaneSamples::kWidth;
    static_assert(kLanes == kSpanLanes, "a window is one block of the shaders");
    LaneSamples lanes(t_, x_first_, x_last_, y_first, pattern_.offsets, pattern_.count);
    float fx[kLanes];
    for (int i = 0; i < kLanes; ++i) fx[i] = float(x_first_ - t_.min_x + i);
    const float z_step = planes_.dx[Planes::kDepth];
    for (int y = y_first; y <= y_last; ++y, lanes.NextRow()) {
      int32_t covered[kLanes];
      if (!lanes.Cover(covered)) continue;
      alignas(32) float at[Planes::kCount];
      planes_.AlongRow(float(y - t_.min_y), at);
      int32_t won[kLanes] = {};
      int any = 0;
      for (int k = 0; k < pattern_.count; ++k) {
        float* depth = target_.Depth(x_first_, y, k);
        const float z_row = at[Planes::kDepth] + depth_offset_[k];
#pragma omp simd reduction(| : any)
        for (int i = 0; i < kLanes; ++i) {
          const float here = z_row + z_step * fx[i];
          const bool nearer = ((covered[i] >> k) & 1) && here < depth[i];
          depth[i] = nearer ? here : depth[i];
          won[i] |= int32_t(nearer) << k;
          any |= nearer;
        }
      }
      if (!any) continue;
      float fx_shaded[kLanes], fy_shaded[kLanes];
      for (int i = 0; i < kLanes; ++i) {
        fx_shaded[i] = fx[i] + pattern_.centroid_x[won[i]];
        fy_shaded[i] = pattern_.centroid_y[won[i]];
      }
      uint32_t colour[kLanes];
      shader.Shade(AtRowOffsets(at, planes_, fy_shaded), fx_shaded, colour);
      for (int k = 0; k < pattern_.count; ++k) {
        uint32_t* rgbx = target_.Rgbx(x_first_, y, k);
#pragma omp simd
        for (int i = 0; i < kLanes; ++i) rgbx[i] = ((won[i] >> k) & 1) ? colour[i] : rgbx[i];
      }
    }
  }

 private:
  /// Row y: the depth test per sample, then shading where any sample won, then the colours.
  template <class Shader>
  void FillRow(const Shader& shader, int y, const SampleSpan row[kMaxSamples]) {
    if (shader.cutout()) return FillRowCutout(shader, y, row);
    int first = INT_MAX, last = -1;
    for (int k = 0; k < pattern_.count; ++k) {
      if (row[k].first > row[k].last) continue;
      first = std::min(first, row[k].first);
      last = std::max(last, row[k].last);
    }
    if (first > last) return;
    const int n = last - first + 1;
    alignas(32) float at[Planes::kCount];
    planes_.AlongRow(float(y - t_.min_y), at);
    int32_t* won = target_.row_mask;
    std::memset(won, 0, size_t(n) * sizeof(*won));
    bool any = false;
    for (int k = 0; k < pattern_.count; ++k) {
      if (row[k].first <= row[k].last)
        any |= DepthTest(k, y, at[Planes::kDepth], row[k], won + (row[k].first - first));
    }
    if (!any) return;
    uint32_t* colour = target_.row_colour;
    ShadeRow(shader, at, first, n, won, colour);
    for (int k = 0; k < pattern_.count; ++k) {
      if (row[k].first <= row[k].last)
        Store(k, y, row[k], won + (row[k].first - first), colour + (row[k].first - first));
    }
  }

  /// Row y of a surface cut by its pattern's alpha (alpha to coverage), kSpanLanes pixels at a
  /// time: each pixel shaded where any sample is inside, at their centre; its alpha keeps
  /// round(alpha n) of the n samples (AlphaSamples), of which those inside and in front are
  /// drawn. So a cut edge is smoothed in n + 1 steps, as a triangle's edge is.
  template <class Shader>
  void FillRowCutout(const Shader& shader, int y, const SampleSpan row[kMaxSamples]) {
    alignas(32) float at[Planes::kCount];
    planes_.AlongRow(float(y - t_.min_y), at);
    const float z_step = planes_.dx[Planes::kDepth];
    for (int x0 = x_first_; x0 <= x_last_; x0 += kSpanLanes) {
      int32_t inside[kSpanLanes] = {};
      int any = 0;
      float fx[kSpanLanes], fy[kSpanLanes];
      for (int i = 0; i < kSpanLanes; ++i) {
        const int x = std::min(x0 + i, x_last_);
        for (int k = 0; k < pattern_.count; ++k)
          inside[i] |= int32_t(row[k].first <= x && x <= row[k].last) << k;
        if (x0 + i > x_last_) inside[i] = 0;
        any |= inside[i];
        fx[i] = float(x - t_.min_x) + pattern_.centroid_x[inside[i]];
        fy[i] = pattern_.centroid_y[inside[i]];
      }
      if (!any) continue;
      uint32_t colour[kSpanLanes];
      float alpha[kSpanLanes];
      shader.Shade(AtRowOffsets(at, planes_, fy), fx, colour, alpha);
      for (int i = 0; i < kSpanLanes && x0 + i <= x_last_; ++i) {
        const int x = x0 + i;
        const int32_t drawn = inside[i] & AlphaSamples(alpha[i], x, y);
        for (int k = 0; k < pattern_.count; ++k) {
          if (!((drawn >> k) & 1)) continue;
          float* depth = target_.Depth(x, y, k);
          const float here = at[Planes::kDepth] + depth_offset_[k] + z_step * float(x - t_.min_x);
          if (!(here < *depth)) continue;
          *depth = here;
          *target_.Rgbx(x, y, k) = colour[i];
        }
      }
    }
  }

  /// The samples of pixel (x, y) that alpha 0..1 covers: round(alpha n) of the n, taken in turn
  /// from a place that moves from pixel to pixel, so that a part-covered area mixes the samples.
  int32_t AlphaSamples(float alpha, int x, int y) const {
    const int n = pattern_.count;
    const int kept = std::clamp(int(alpha * float(n) + 0.5f), 0, n);
    const int start = (x + 3 * y) % n;
    const int32_t run = int32_t((1u << kept) - 1u);  // kept bits from bit 0, rotated to start
    return ((run << start) | (run >> (n - start))) & int32_t((1u << n) - 1u);
  }

  /// Sample k's depth test along its span: nearer depths written, bit k set in won[] where so.
  bool DepthTest(int k, int y, float depth_along_row, SampleSpan span, int32_t* won) const {
    float* depth = target_.Depth(span.first, y, k);
    const float z_row = depth_along_row + depth_offset_[k], z_step = planes_.dx[Planes::kDepth];
    const float fx0 = float(span.first - t_.min_x);
    const int32_t bit = 1 << k;
    const int n = span.last - span.first + 1;
    int any = 0;
#pragma omp simd reduction(| : any)
    for (int i = 0; i < n; ++i) {
      const float here = z_row + z_step * (fx0 + float(i));
      const bool nearer = here < depth[i];
      depth[i] = nearer ? here : depth[i];
      won[i] |= nearer ? bit : 0;
      any |= nearer;
    }
    return any;
  }

  /// Colours of the n pixels from column `first`, kSpanLanes at a time where any sample won.
  template <class Shader>
  void ShadeRow(const Shader& shader, const float at[Planes::kCount], int first, int n, const int32_t* won,
                uint32_t* colour) const {
    for (int start = 0; start < n; start += kSpanLanes) {
      int any = 0;
      float fx[kSpanLanes], fy[kSpanLanes];
      for (int i = 0; i < kSpanLanes; ++i) {
        const int32_t mask = start + i < n ? won[start + i] : 0;
        any |= mask;
        fx[i] = float(first - t_.min_x + std::min(start + i, n - 1)) + pattern_.centroid_x[mask];
        fy[i] = pattern_.centroid_y[mask];
      }
      if (any) shader.Shade(AtRowOffsets(at, planes_, fy), fx, colour + start);
    }
  }

  /// Sample k's colours where bit k of won[] is set.
  void Store(int k, int y, SampleSpan span, const int32_t* won, const uint32_t* colour) const {
    uint32_t* rgbx = target_.Rgbx(span.first, y, k);
    const int32_t bit = 1 << k;
    const int n = span.last - span.first + 1;
#pragma omp simd
    for (int i = 0; i < n; ++i) rgbx[i] = (won[i] & bit) ? colour[i] : rgbx[i];
  }

  const TriangleSetup& t_;
  const Planes& planes_;
  const SamplePattern& pattern_;
  const TileTarget& target_;
  int x_first_, x_last_;
  float depth_offset_[kMaxSamples] = {};
};

}  // namespace

void RasterizeMultisampled(const TriangleSetup& t, const ShadeContext& context, const TileTarget& target) {
  const TileRect& tile = target.rect;
  const int y_first = std::max(t.min_y, tile.y0), y_last = std::min(t.max_y, tile.y1 - 1);
  const int x_first = std::max(t.min_x, tile.x0), x_last = std::min(t.max_x, tile.x1 - 1);
  if (y_first > y_last || x_first > x_last) return;
  const SamplePattern& pattern = context.samples;
  const BoxCover cover = CoverOfBox(t, x_first, y_first, x_last, y_last, pattern.reach);  // narrow: cheap too
  if (cover == BoxCover::kNone) return;
  const Planes planes(t);
  MultisampledRows rows(t, planes, pattern, target, x_first, x_last);
  const bool whole = cover == BoxCover::kAll;
  const bool in_window = t.narrow && x_last - x_first < LaneSamples::kWidth;
  const auto fill = [&](const auto& shader) {
    if (in_window && !shader.cutout()) {
      rows.FillNarrow(shader, y_first, y_last);
    } else {
      rows.Fill(shader, y_first, y_last, whole);
    }
  };
  WithShader(t, context, planes, x_first, y_first, x_last, y_last, fill);
}

}  // namespace flagsim::render
