#include "server/render/triangle_setup.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace flagsim::render {
namespace {

int64_t Snap(float pixels) { return static_cast<int64_t>(std::lround(double(pixels) * kSubpixels)); }

/// Edge i's E + bias at the centre of pixel (x, y) moved by `offset`, in subpixels squared,
/// E(P) = dx (Py - y_i) - dy (Px - x_i): >= 0 inside.
int64_t EdgeAt(const TriangleSetup& setup, int i, int x, int y, SampleOffset offset = {}) {
  const int64_t half = kSubpixels / 2;
  return setup.edge_dx[i] * (int64_t(y) * kSubpixels + half + offset.y - setup.edge_y[i]) -
         setup.edge_dy[i] * (int64_t(x) * kSubpixels + half + offset.x - setup.edge_x[i]) + setup.edge_bias[i];
}

/// floor(a / b) for b > 0.
int64_t FloorDiv(int64_t a, int64_t b) { return a / b - ((a % b != 0) && (a < 0)); }

/// The plane through (x_i, y_i, value_i), with its origin at pixel centre (x0 + 0.5, y0 + 0.5).
Plane FitPlane(const float x[3], const float y[3], const float value[3], float area2, int x0, int y0) {
  Plane plane;
  const float e1x = x[1] - x[0], e1y = y[1] - y[0], e2x = x[2] - x[0], e2y = y[2] - y[0];
  const float d1 = value[1] - value[0], d2 = value[2] - value[0];
  plane.dx = (d1 * e2y - d2 * e1y) / area2;
  plane.dy = (d2 * e1x - d1 * e2x) / area2;
  plane.origin = value[0] + plane.dx * (x0 + 0.5f - x[0]) + plane.dy * (y0 + 0.5f - y[0]);
  return plane;
}

}  // namespace

bool IsBackFacing(const ScreenVertex& a, const ScreenVertex& b, const ScreenVertex& c) {
  // Counter-clockwise in the world's view (OpenGL's front) is clockwise once y points down,
  // which makes this (snapped, so exactly the setup's) area negative.
  const int64_t ax = Snap(a.x), ay = Snap(a.y);
  return (Snap(b.x) - ax) * (Snap(c.y) - ay) - (Snap(b.y) - ay) * (Snap(c.x) - ax) > 0;
}

bool SetupTriangle(const ScreenVertex& a, const ScreenVertex& b, const ScreenVertex& c, int width, int height,
                   TriangleSetup* setup, int sample_reach) {
  // Order the vertices so that the snapped area is positive: then inside means E >= 0.
  const ScreenVertex* v[3] = {&a, &b, &c};
  int64_t X[3], Y[3];
  for (int i = 0; i < 3; ++i) {
    X[i] = Snap(v[i]->x);
    Y[i] = Snap(v[i]->y);
  }
  int64_t area2 = (X[1] - X[0]) * (Y[2] - Y[0]) - (Y[1] - Y[0]) * (X[2] - X[0]);
  if (area2 == 0) return false;
  setup->back_facing = area2 > 0;
  if (area2 < 0) {
    std::swap(v[1], v[2]);
    std::swap(X[1], X[2]);
    std::swap(Y[1], Y[2]);
    area2 = -area2;
  }

  // Pixels with a sample (p + 1/2, moved up to sample_reach) in the box of the snapped
  // vertices, inside the image.
  const int64_t half = kSubpixels / 2;
  const auto first_pixel = [&](int64_t low) { return -FloorDiv(half - low, kSubpixels); };  // ceil
  const auto last_pixel = [&](int64_t high) { return FloorDiv(high - half, kSubpixels); };
  setup->min_x = int(std::max<int64_t>(0, first_pixel(std::min({X[0], X[1], X[2]}) - sample_reach)));
  setup->min_y = int(std::max<int64_t>(0, first_pixel(std::min({Y[0], Y[1], Y[2]}) - sample_reach)));
  setup->max_x = int(std::min<int64_t>(width - 1, last_pixel(std::max({X[0], X[1], X[2]}) + sample_reach)));
  setup->max_y = int(std::min<int64_t>(height - 1, last_pixel(std::max({Y[0], Y[1], Y[2]}) + sample_reach)));
  if (setup->min_x > setup->max_x || setup->min_y > setup->max_y) return false;

  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    setup->edge_x[i] = int32_t(X[i]);
    setup->edge_y[i] = int32_t(Y[i]);
    setup->edge_dx[i] = int32_t(X[j] - X[i]);
    setup->edge_dy[i] = int32_t(Y[j] - Y[i]);
    // With y down and positive area the vertices run clockwise on screen: a top edge is
    // horizontal going right, a left edge goes up.
    const bool top = setup->edge_dy[i] == 0 && setup->edge_dx[i] > 0;
    const bool left = setup->edge_dy[i] < 0;
    setup->edge_bias[i] = top || left ? 0 : -1;
  }
  // LaneSpans' int32 holds E: with the vertices within W = kWidth px across and H = 256 px
  // down, pixel centres in a window are within W + kWidth px across and H + 1 px down of each
  // vertex, so |E| <= |dx| (H + 1) + |dy| (W + kWidth) <= (8 * 257 + 256 * 16) px^2 * 256^2 < 2^31.
  setup->narrow =
      std::max({X[0], X[1], X[2]}) - std::min({X[0], X[1], X[2]}) <= LaneSpans::kWidth * kSubpixels &&
      std::max({Y[0], Y[1], Y[2]}) - std::min({Y[0], Y[1], Y[2]}) <= 256 * kSubpixels;

  float x[3], y[3], values[3];
  for (int i = 0; i < 3; ++i) {
    x[i] = float(X[i]) / kSubpixels;
    y[i] = float(Y[i]) / kSubpixels;
  }
  const float area = float(area2) / float(kSubpixels * kSubpixels);
  const auto fit = [&](auto field) {
    for (int i = 0; i < 3; ++i) values[i] = field(*v[i]);
    return FitPlane(x, y, values, area, setup->min_x, setup->min_y);
  };
  setup->depth = fit([](const ScreenVertex& s) { return s.z; });
  setup->inverse_w = fit([](const ScreenVertex& s) { return s.inverse_w; });
  for (int k = 0; k < kPlaneChannels; ++k) {
    setup->channels[k] = fit([k](const ScreenVertex& s) { return s.channels[k] * s.inverse_w; });
  }
  return true;
}

RowSpans::RowSpans(const TriangleSetup& setup, int y, SampleOffset sample)
    : min_x_(setup.min_x), max_x_(setup.max_x) {
  const int64_t py = int64_t(y) * kSubpixels + kSubpixels / 2 + sample.y;
  for (int i = 0; i < 3; ++i) {
    // As in RowSpan: inside when K + bias >= m px, K growing by dx * kSubpixels a row.
    const int64_t dy = setup.edge_dy[i];
    const int64_t k = setup.edge_dx[i] * (py - setup.edge_y[i]) +
                      dy * (setup.edge_x[i] - kSubpixels / 2 - sample.x) + setup.edge_bias[i];
    const int64_t growth = setup.edge_dx[i] * kSubpixels;
    Edge& edge = edges_[i];
    const int64_t m = dy * kSubpixels;
    edge.sign = m > 0 ? 1 : m < 0 ? -1 : 0;
    if (edge.sign == 0) {
      edge.quotient = k;
      edge.step_quotient = growth;
      continue;
    }
    edge.divisor = m > 0 ? m : -m;
    edge.quotient = FloorDiv(k, edge.divisor);
    edge.remainder = k - edge.quotient * edge.divisor;
    edge.step_quotient = FloorDiv(growth, edge.divisor);
    edge.step_remainder = growth - edge.step_quotient * edge.divisor;
  }
}

bool RowSpans::Span(int* first, int* last) const {
  int64_t low = min_x_, high = max_x_;
  for (const Edge& edge : edges_) {
    if (edge.sign > 0) {
      high = std::min(high, edge.quotient);  // px <= floor(K / m)
    } else if (edge.sign < 0) {
      low = std::max(low, -edge.quotient);  // px >= -floor(K / |m|)
    } else if (edge.quotient < 0) {
      return false;  // a horizontal edge with the row outside
    }
  }
  *first = int(low);
  *last = int(high);
  return low <= high;
}

void RowSpans::NextRow() {
  for (Edge& edge : edges_) {
    edge.quotient += edge.step_quotient;
    if (edge.sign == 0) continue;
    edge.remainder += edge.step_remainder;
    if (edge.remainder >= edge.divisor) {
      edge.remainder -= edge.divisor;
      ++edge.quotient;
    }
  }
}

LaneSpans::LaneSpans(const TriangleSetup& setup, int x0, int x_last, int y) : x0_(x0) {
  for (int i = 0; i < kWidth; ++i) past_end_[i] = x0 + i > x_last ? -1 : 0;
  for (int k = 0; k < 3; ++k) {
    growth_[k] = int32_t(setup.edge_dx[k] * kSubpixels);
    const int64_t at_x0 = EdgeAt(setup, k, x0, y), per_pixel = -int64_t(setup.edge_dy[k]) * kSubpixels;
    for (int i = 0; i < kWidth; ++i) inside_[k][i] = int32_t(at_x0 + per_pixel * i);
  }
}

LaneSamples::LaneSamples(const TriangleSetup& setup, int x0, int x_last, int y, const SampleOffset* offsets,
                         int count)
    : centres_(setup, x0, x_last, y), count_(count) {
  // |ox|, |oy| < kSubpixels / 2 keeps LaneSpans' bound on |E| well within int32.
  for (int e = 0; e < 3; ++e) {
    for (int k = 0; k < count; ++k)
      shift_[k][e] = int32_t(int64_t(setup.edge_dx[e]) * offsets[k].y - int64_t(setup.edge_dy[e]) * offsets[k].x);
  }
}

BoxCover CoverOfBox(const TriangleSetup& setup, int x0, int y0, int x1, int y1, int sample_reach) {
  bool all = true;
  const int r = sample_reach;
  for (int i = 0; i < 3; ++i) {
    int inside = 0;
    for (const auto& [x, ox] : {std::pair{x0, -r}, std::pair{x1, r}}) {
      for (const auto& [y, oy] : {std::pair{y0, -r}, std::pair{y1, r}}) {
        inside += EdgeAt(setup, i, x, y, SampleOffset{ox, oy}) >= 0;
      }
    }
    if (inside == 0) return BoxCover::kNone;
    all = all && inside == 4;
  }
  return all ? BoxCover::kAll : BoxCover::kPart;
}

bool RowSpan(const TriangleSetup& setup, int y, int* first, int* last) {
  int64_t low = setup.min_x, high = setup.max_x;
  const int64_t py = int64_t(y) * kSubpixels + kSubpixels / 2;
  for (int i = 0; i < 3; ++i) {
    // E(px) = K - M px with px the pixel index; inside when K + bias >= M px.
    const int64_t dy = setup.edge_dy[i];
    const int64_t k = setup.edge_dx[i] * (py - setup.edge_y[i]) + dy * (setup.edge_x[i] - kSubpixels / 2) +
                      setup.edge_bias[i];
    const int64_t m = dy * kSubpixels;
    if (m > 0) {
      high = std::min(high, FloorDiv(k, m));
    } else if (m < 0) {
      low = std::max(low, -FloorDiv(k, -m));  // px >= ceil(-k / -m)
    } else if (k < 0) {
      return false;
    }
  }
  *first = int(low);
  *last = int(high);
  return low <= high;
}

}  // namespace flagsim::render
