#include "server/lab/screen_error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace flagsim::lab {
namespace {

// world => clip => normalised device => pixels (x right, y down)
bool ToPixel(const Eigen::Matrix4d& clip_from_world, const render::Camera& camera, double x, double y,
             double z, Eigen::Vector2d* pixel) {
  const Eigen::Vector4d clip = clip_from_world * Eigen::Vector4d(x, y, z, 1.0);
  if (clip.w() <= 0) return false;
  *pixel = Eigen::Vector2d((clip.x() / clip.w() + 1) * 0.5 * camera.width,
                           (1 - clip.y() / clip.w()) * 0.5 * camera.height);
  return true;
}

}  // namespace

ScreenError ScreenDistance(const render::Camera& camera, const sim::ClothState<double>& a,
                           const sim::ClothState<double>& b) {
  const Eigen::Matrix4d clip_from_world = camera.Projection() * camera.View();
  ScreenError error;
  double sum = 0;
  const int n = a.num_nodes();
  for (int i = 0; i < n; ++i) {
    Eigen::Vector2d pa, pb;
    double distance = std::numeric_limits<double>::infinity();
    if (ToPixel(clip_from_world, camera, a.x[i], a.y[i], a.z[i], &pa) &&
        ToPixel(clip_from_world, camera, b.x[i], b.y[i], b.z[i], &pb)) {
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
