#include "lab/screen_error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace flagsim::lab {

ScreenError ScreenDistance(const render::Camera& camera, const sim::ClothState<double>& a,
                           const sim::ClothState<double>& b) {
  const Eigen::Matrix4d clip_from_world = camera.Projection() * camera.View();
  ScreenError error;
  double sum = 0;
  const int n = a.num_nodes();
  for (int i = 0; i < n; ++i) {
    Eigen::Vector2d pa, pb;
    double distance = std::numeric_limits<double>::infinity();
    if (render::ToPixel(clip_from_world, camera, a.x[i], a.y[i], a.z[i], &pa) &&
        render::ToPixel(clip_from_world, camera, b.x[i], b.y[i], b.z[i], &pb)) {
      distance = (pa - pb).norm();
    }
    if (std::isnan(distance)) distance = std::numeric_limits<double>::infinity();
    sum += distance * distance;
    error.largest = std::max(error.largest, distance);
  }
  error.rms = n > 0 ? std::sqrt(sum / n) : 0.0;
  return error;
}

}  // namespace flagsim::lab
