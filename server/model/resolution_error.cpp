#include "server/model/resolution_error.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "server/sim/bending.hpp"

namespace flagsim::model {
namespace {

constexpr double kPercentile = 0.95;

double Percentile(std::vector<double> values) {
  if (values.empty()) return 0;
  const size_t rank = std::min(values.size() - 1, size_t(std::ceil(kPercentile * values.size())) - 1);
  std::nth_element(values.begin(), values.begin() + rank, values.end());
  return values[rank];
}

}  // namespace

template <typename Real>
ClothOnScreen MeasureClothOnScreen(const sim::ClothModel<Real>& model, const sim::ClothState<Real>& state,
                                   const render::Camera& camera) {
  std::vector<double> curvatures;
  for (int r = 1; r + 1 < model.rows; ++r) {
    for (int c = 1; c + 1 < model.cols; ++c) {
      const std::array<double, 3> k = sim::CurvatureAt(model, state.x, state.y, state.z, r, c);
      curvatures.push_back(std::sqrt(k[0] * k[0] + k[1] * k[1] + k[2] * k[2]));
    }
  }
  const Eigen::Matrix4d clip_from_world = camera.Projection() * camera.View();
  std::vector<Eigen::Vector2d> pixel(model.num_nodes());
  std::vector<bool> seen(model.num_nodes());
  for (int i = 0; i < model.num_nodes(); ++i) {
    seen[i] = render::ToPixel(clip_from_world, camera, state.x[i], state.y[i], state.z[i], &pixel[i]);
  }
  std::vector<double> scales;  // px per metre of rest length, along the rows and down the columns
  for (int r = 0; r < model.rows; ++r) {
    for (int c = 0; c < model.cols; ++c) {
      const int i = model.index(r, c);
      if (c + 1 < model.cols && seen[i] && seen[i + 1]) scales.push_back((pixel[i + 1] - pixel[i]).norm() / model.dx);
      if (r + 1 < model.rows && seen[i] && seen[i + model.cols]) {
        scales.push_back((pixel[i + model.cols] - pixel[i]).norm() / model.dy);
      }
    }
  }
  return {Percentile(curvatures), Percentile(scales)};
}

double ResolutionErrorPx(const ClothOnScreen& cloth, double width, double height, int cols, int rows) {
  const double h = std::max(width / (cols - 1), height / (rows - 1));
  return h * h * cloth.curvature / 8 * cloth.pixels_per_metre;
}

template ClothOnScreen MeasureClothOnScreen<float>(const sim::ClothModel<float>&, const sim::ClothState<float>&,
                                                   const render::Camera&);
template ClothOnScreen MeasureClothOnScreen<double>(const sim::ClothModel<double>&, const sim::ClothState<double>&,
                                                    const render::Camera&);

}  // namespace flagsim::model
