// Triangle setup: a projected triangle snapped to a fixed-point grid, with its three edge
// functions and the planes its attributes are interpolated on.
//
// Coverage follows the edge functions exactly: vertices are snapped to 1/256 px, a pixel is
// covered when its centre is inside all three edges, and a centre exactly on an edge belongs
// to the triangle only if that edge is a top or a left edge. Two triangles sharing an edge
// therefore cover each pixel along it exactly once, and nothing between them is left out.
// Coverage is computed a row at a time, as the span of x where all three edge functions pass
// (integer arithmetic, so exact), which leaves the per-pixel loop with no edge tests at all.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cstdint>

namespace flagsim::render {

constexpr int kSubpixelBits = 8;
constexpr int64_t kSubpixels = int64_t(1) << kSubpixelBits;  ///< per pixel
constexpr int kPlaneChannels = 8;                            ///< attributes interpolated per pixel

/// a(x, y) = origin + dx (x - x0) + dy (y - y0), with (x0, y0) the centre of the box's first pixel.
struct Plane {
  float origin = 0, dx = 0, dy = 0;
};

/// A sample's place relative to the pixel centre, in subpixels (sample_pattern.hpp).
struct SampleOffset {
  int x = 0, y = 0;
};
constexpr int kMaxSamples = 8;  ///< per pixel

/// One projected vertex: window position and what is interpolated.
struct ScreenVertex {
  float x = 0, y = 0;   ///< px from the top-left corner of the image, y down
  float z = 0;          ///< window depth, 0 (near) .. 1 (far)
  float inverse_w = 0;  ///< 1 / w_clip, for perspective-correct interpolation
  float channels[kPlaneChannels] = {};
};

struct TriangleSetup {
  int min_x = 0, min_y = 0, max_x = -1, max_y = -1;  ///< px, inclusive, inside the image
  // Edge i runs from vertex i to vertex i + 1, in subpixels: E(P) = dx (Py - y) - dy (Px - x),
  // worked out in int64. (Clipped to the guard band, vertices are within a few image widths.)
  int32_t edge_x[3] = {}, edge_y[3] = {}, edge_dx[3] = {}, edge_dy[3] = {};
  int32_t edge_bias[3] = {};       ///< 0 for top and left edges, -1 for the others
  Plane depth;                     ///< window depth, linear in the image
  Plane inverse_w;                 ///< 1 / w
  Plane channels[kPlaneChannels];  ///< channel / w: divide by inverse_w for the channel
  bool back_facing = false;        ///< the vertices run clockwise as seen (after the y flip: counter)
  bool narrow = false;             ///< small enough for LaneSpans in any window
  int material = 0;                ///< index into the scene's materials
  float uv_area_per_pixel = 0;     ///< (u, v) area per px² of the image: the pattern's level of detail
};

/// Snaps and sets up the triangle; false if its box holds no pixel of a width x height image.
/// The box holds the pixels whose samples, up to `sample_reach` subpixels from the centre in x
/// and y (0: the centre alone), may fall inside the vertices' box. `back_facing` is reported
/// from the winding; vertex order is then fixed internally.
bool SetupTriangle(const ScreenVertex& a, const ScreenVertex& b, const ScreenVertex& c, int width, int height,
                   TriangleSetup* setup, int sample_reach = 0);

/// The winding of a projected triangle before setup: true if it faces away from the camera.
bool IsBackFacing(const ScreenVertex& a, const ScreenVertex& b, const ScreenVertex& c);

/// The covered pixels of row y: [*first, *last] within [min_x, max_x]; false if none.
bool RowSpan(const TriangleSetup& setup, int y, int* first, int* last);

/// How much of a box of pixels inside the triangle's box is covered.
enum class BoxCover { kNone, kPart, kAll };

/// Pixels [x0, x1] x [y0, y1] (inclusive, within min_x .. max_x, min_y .. max_y), from the edge
/// functions at the four corner pixels' centres, moved out by `sample_reach` subpixels to hold
/// every sample: each is linear, so all four outside one edge leave the box uncovered, and all
/// four inside every edge cover it all.
BoxCover CoverOfBox(const TriangleSetup& setup, int x0, int y0, int x1, int y1, int sample_reach = 0);

/// The same spans row after row, with no division per row: each edge's bound floor(K / m)
/// is carried as quotient and remainder, and K grows by the same amount every row.
class RowSpans {
 public:
  RowSpans() = default;  ///< no span on any row, until assigned
  /// Positioned at row y, testing each pixel at its centre moved by `sample`.
  RowSpans(const TriangleSetup& setup, int y, SampleOffset sample = {});
  bool Span(int* first, int* last) const;  ///< this row's covered pixels; false if none
  void NextRow();

 private:
  struct Edge {
    int64_t quotient = 0, remainder = 0;  ///< floor(K / |m|) and K mod |m| (m != 0); K itself (m == 0)
    int64_t step_quotient = 0, step_remainder = 0;  ///< the same for K's growth per row
    int64_t divisor = 0;                            ///< |m|
    int sign = 0;                                   ///< of m: +1 bounds from above, -1 from below
  };
  Edge edges_[3];
  int min_x_ = 0, max_x_ = -1;
};

/// The same spans in a window of kWidth columns from x0, for narrow triangles: each edge
/// function evaluated at the window's pixel centres in int32, a row's span the lanes inside all
/// three edges. No division, no branch per edge.
class LaneSpans {
 public:
  static constexpr int kWidth = 8;  ///< px

  /// Positioned at row y, spans limited to columns x0 .. x_last (x_last - x0 < kWidth), for a
  /// `narrow` setup.
  LaneSpans(const TriangleSetup& setup, int x0, int x_last, int y);
  bool Span(int* first, int* last) const;  ///< this row's covered pixels; false if none
  void NextRow();

 private:
  int32_t inside_[3][kWidth];  ///< E + bias at each lane's pixel centre: >= 0 inside the edge
  int32_t growth_[3];          ///< of E a row
  int32_t past_end_[kWidth];   ///< -1 for lanes past x_last, else 0
  int x0_;                     ///< the window's first column

  friend class LaneSamples;  ///< tests its samples against these centres
};

// Inline: a narrow triangle's rows are short, and a call would cost as much as either.
inline bool LaneSpans::Span(int* first, int* last) const {
  // Inside all three edges and not past x_last: no sign bit in the or. Covered lanes are contiguous.
  int low = kWidth, high = -1;
#pragma omp simd reduction(min : low) reduction(max : high)
  for (int i = 0; i < kWidth; ++i) {
    const bool covered = (inside_[0][i] | inside_[1][i] | inside_[2][i] | past_end_[i]) >= 0;
    low = std::min(low, covered ? i : kWidth);
    high = std::max(high, covered ? i : -1);
  }
  *first = x0_ + low;
  *last = x0_ + high;
  return low <= high;
}

inline void LaneSpans::NextRow() {
  for (int k = 0; k < 3; ++k) {
#pragma omp simd
    for (int i = 0; i < kWidth; ++i) inside_[k][i] += growth_[k];
  }
}

/// LaneSpans' window, multisampled: per row, each lane's covered samples as bits. The edge
/// functions at the lanes' centres are LaneSpans'; a sample (ox, oy) from the centre moves each
/// by the same dx oy - dy ox in every lane and row.
class LaneSamples {
 public:
  static constexpr int kWidth = LaneSpans::kWidth;

  /// Positioned at row y, lanes limited to columns x0 .. x_last (x_last - x0 < kWidth), samples
  /// at `offsets` (`count` of them, up to kMaxSamples, each within 1/2 px), for a `narrow` setup.
  LaneSamples(const TriangleSetup& setup, int x0, int x_last, int y, const SampleOffset* offsets, int count);
  /// This row's coverage: bit k of covered[i] set where lane i's sample k is inside; false if none.
  bool Cover(int32_t covered[kWidth]) const;
  void NextRow() { centres_.NextRow(); }

 private:
  LaneSpans centres_;
  int32_t shift_[kMaxSamples][3];  ///< E at sample k less E at the centre, per edge
  int count_;
};

inline bool LaneSamples::Cover(int32_t covered[kWidth]) const {
  const auto& inside = centres_.inside_;
  int any = 0;
  for (int i = 0; i < kWidth; ++i) covered[i] = 0;
  for (int k = 0; k < count_; ++k) {
    const int32_t* shift = shift_[k];
#pragma omp simd reduction(| : any)
    for (int i = 0; i < kWidth; ++i) {
      const int32_t in = ((inside[0][i] + shift[0]) | (inside[1][i] + shift[1]) | (inside[2][i] + shift[2]) |
                          centres_.past_end_[i]) >= 0;
      covered[i] |= in << k;
      any |= in;
    }
  }
  return any != 0;
}

}  // namespace flagsim::render
