#include "camera.hpp"

#include <algorithm>
#include <cmath>

namespace flagsim::render {

Eigen::Matrix4d Camera::View() const {
  const Eigen::Vector3d forward = (target - eye).normalized();
  const Eigen::Vector3d right = forward.cross(up).normalized();
  const Eigen::Vector3d true_up = right.cross(forward);
  Eigen::Matrix4d look = Eigen::Matrix4d::Identity();
  look.block<1, 3>(0, 0) = right.transpose();
  look.block<1, 3>(1, 0) = true_up.transpose();
  look.block<1, 3>(2, 0) = -forward.transpose();
  look(0, 3) = -right.dot(eye);
  look(1, 3) = -true_up.dot(eye);
  look(2, 3) = forward.dot(eye);
  return look * scene.matrix();
}

Eigen::Matrix4d Camera::Projection() const {
  const double f = 1.0 / std::tan(fov_y / 2), aspect = double(width) / height;
  const double n = near_plane, fa = far_plane;
  Eigen::Matrix4d projection = Eigen::Matrix4d::Zero();
  projection(0, 0) = f / aspect;
  projection(1, 1) = f;
  projection(2, 2) = (fa + n) / (n - fa);
  projection(2, 3) = 2 * fa * n / (n - fa);
  projection(3, 2) = -1;
  return projection;
}

// Both moves act on the world as it is shown now (they multiply `scene` from the left): the
// seed's T(p) R T(-p) and T(p) S T(-p).
void Camera::RotateScene(const Eigen::Vector3d& axis, double angle) {
  scene = Eigen::Translation3d(target) * Eigen::AngleAxisd(angle, axis.normalized()) *
          Eigen::Translation3d(-target) * scene;
}

void Camera::ScaleScene(double factor, const Eigen::Vector3d& centre) {
  scene = Eigen::Translation3d(centre) * Eigen::Scaling(factor) * Eigen::Translation3d(-centre) * scene;
}

void Camera::Translate(const Eigen::Vector3d& offset) {
  eye += offset;
  target += offset;
}

void Camera::Orbit(double azimuth, double elevation) {
  const Eigen::Vector3d arm = eye - target;
  const double radius = arm.norm();
  double theta = std::atan2(arm.x(), arm.z()) + azimuth;
  double phi = std::asin(std::clamp(arm.y() / radius, -1.0, 1.0)) + elevation;
  phi = std::clamp(phi, -1.5, 1.5);  // stop short of the poles, where up is undefined
  eye = target + radius * Eigen::Vector3d(std::cos(phi) * std::sin(theta), std::sin(phi),
                                          std::cos(phi) * std::cos(theta));
}

}  // namespace flagsim::render
