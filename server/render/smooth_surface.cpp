#include "server/render/smooth_surface.hpp"

#include <algorithm>
#include <cmath>

namespace flagsim::render {
namespace {

/// The Catmull-Rom point at t in [0, 1] between b and c, with a before b and d after c.
float CatmullRom(float a, float b, float c, float d, float t) {
  return 0.5f * (2 * b + (c - a) * t + (2 * a - 5 * b + 4 * c - d) * t * t + (3 * b - a - 3 * c + d) * t * t * t);
}

/// `count` values at `stride` apart from `in`, refined `factor` times into `out` (stride `out_stride`):
/// (count - 1) factor + 1 values, the i-th node's at i factor.
void RefineLine(const float* in, int count, int stride, int factor, float* out, int out_stride) {
  const auto node = [&](int i) {  // mirrored past either end
    if (i < 0) return 2 * in[0] - in[stride];
    if (i >= count) return 2 * in[size_t(count - 1) * stride] - in[size_t(count - 2) * stride];
    return in[size_t(i) * stride];
  };
  for (int i = 0; i + 1 < count; ++i) {
    const float a = node(i - 1), b = node(i), c = node(i + 1), d = node(i + 2);
    for (int k = 0; k < factor; ++k) out[size_t(i * factor + k) * out_stride] = CatmullRom(a, b, c, d, float(k) / factor);
  }
  out[size_t((count - 1) * factor) * out_stride] = in[size_t(count - 1) * stride];
}

}  // namespace

int RefinementFor(const NodeGrid& grid, const Camera& camera) {
  if (grid.cols < 2 || grid.rows < 2) return 1;
  const Eigen::Vector3d eye = camera.EyeInWorld();
  double nearest = INFINITY, cell = 0;
  for (int r = 0; r < grid.rows; ++r) {
    for (int c = 0; c < grid.cols; ++c) {
      const size_t i = size_t(r) * grid.cols + c;
      const Eigen::Vector3d p(grid.x[i], grid.y[i], grid.z[i]);
      nearest = std::min(nearest, (p - eye).norm());
      if (c + 1 < grid.cols) cell = std::max(cell, (Eigen::Vector3d(grid.x[i + 1], grid.y[i + 1], grid.z[i + 1]) - p).norm());
      if (r + 1 < grid.rows) {
        const size_t j = i + size_t(grid.cols);
        cell = std::max(cell, (Eigen::Vector3d(grid.x[j], grid.y[j], grid.z[j]) - p).norm());
      }
    }
  }
  const double pixels_per_metre = camera.height / (2 * std::max(nearest, 1e-3) * std::tan(camera.fov_y / 2));
  const double cell_pixels = cell * pixels_per_metre;
  return std::clamp(int(std::ceil(cell_pixels / kTargetCellPixels)), 1, kMaxRefinement);
}

// rows along their columns, then the columns of that along the rows: the tensor-product surface
void RefineGrid(const NodeGrid& grid, int factor, float pole_radius, NodeGrid* refined) {
  factor = std::max(factor, 1);
  const int cols = (grid.cols - 1) * factor + 1, rows = (grid.rows - 1) * factor + 1;
  refined->cols = cols;
  refined->rows = rows;
  std::vector<float> along(size_t(grid.rows) * cols);
  for (auto [in, out] : {std::pair{&grid.x, &refined->x}, std::pair{&grid.y, &refined->y}, std::pair{&grid.z, &refined->z}}) {
    out->resize(size_t(cols) * rows);
    for (int r = 0; r < grid.rows; ++r)
      RefineLine(in->data() + size_t(r) * grid.cols, grid.cols, 1, factor, along.data() + size_t(r) * cols, 1);
    for (int c = 0; c < cols; ++c) RefineLine(along.data() + c, grid.rows, cols, factor, out->data() + c, cols);
  }
  if (factor == 1) return;
  for (size_t i = 0; i < refined->x.size(); ++i) {  // out of the pole
    const float radial = std::hypot(refined->x[i], refined->z[i]);
    if (radial >= pole_radius || radial == 0) continue;
    refined->x[i] *= pole_radius / radial;
    refined->z[i] *= pole_radius / radial;
  }
}

}  // namespace flagsim::render
