#include "server/render/camera.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace flagsim::render {
namespace {

/// m: heights this far below the floor count as on it, so that rounding never stops an eye that
/// moves along the ground (an orbit round at the least height, a zoom level with it).
constexpr double kGroundSlack = 1e-10;

/// The eye's world height along an arc of its orbit. On the arc the eye is at
/// centre + cos(a) u + sin(a) v in the camera's frame, and `scene` is affine, so
///   h(a) = mean + b cos a + c sin a,   mean = w . centre + t,  b = w . u,  c = w . v,
/// with w and t the y rows of scene^-1's linear part and translation.
struct ArcHeight {
  double mean = 0, b = 0, c = 0;  ///< m

  ArcHeight(const Eigen::Affine3d& world, const Eigen::Vector3d& centre, const Eigen::Vector3d& u,
            const Eigen::Vector3d& v) {
    const Eigen::Vector3d w = world.linear().row(1).transpose();
    mean = w.dot(centre) + world.translation().y();
    b = w.dot(u);
    c = w.dot(v);
  }
  double operator()(double a) const { return mean + b * std::cos(a) + c * std::sin(a); }
};

/// rad: how far the eye goes on the arc from `from` toward `to` before its height first drops
/// below `floor` (h(from) >= floor, within kGroundSlack); `to` if it never does. h'(a) = c cos a - b sin a
/// vanishes at atan2(c, b) + k pi, so h is monotone between those angles: the first piece of the way that
/// ends below the floor holds the crossing, found by bisection with the eye kept at or above it.
double Reach(const ArcHeight& height, double from, double to, double floor) {
  const double extremum = std::atan2(height.c, height.b);
  const double low = std::min(from, to), high = std::max(from, to);
  std::vector<double> ends;  // the extrema strictly between, in the order the eye meets them
  for (double k = std::ceil((low - extremum) / M_PI); extremum + k * M_PI < high; ++k) {
    if (extremum + k * M_PI > low) ends.push_back(extremum + k * M_PI);
  }
  if (to < from) std::reverse(ends.begin(), ends.end());
  ends.push_back(to);
  double start = from;
  for (const double end : ends) {
    if (height(end) >= floor - kGroundSlack) {
      start = end;
      continue;
    }
    double above = start, below = end;  // h(above) >= floor > h(below)
    for (int i = 0; i < 200; ++i) {
      const double middle = 0.5 * (above + below);
      if (middle == above || middle == below) break;
      (height(middle) >= floor ? above : below) = middle;
    }
    return above;
  }
  return to;
}

}  // namespace

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

// The eye at (theta, phi) about the target: target + r (cos phi sin theta, sin phi, cos phi cos theta).
// It goes round at its elevation (a horizontal circle in the camera's frame), then up or down
// at its new azimuth (a vertical one), and stops where its height would first drop below the
// floor: kMinEyeHeight, or its own height if that is lower.
void Camera::Orbit(double azimuth, double elevation) {
  const Eigen::Vector3d arm = eye - target;
  const double radius = arm.norm();
  if (radius == 0) return;
  const double theta0 = std::atan2(arm.x(), arm.z());
  const double phi0 = std::asin(std::clamp(arm.y() / radius, -1.0, 1.0));
  const double phi1 = std::clamp(phi0 + elevation, -1.5, 1.5);  // short of the poles, where up is undefined
  const Eigen::Affine3d world = scene.inverse();
  const double floor = std::min(kMinEyeHeight, EyeHeight());
  const Eigen::Vector3d up_axis = Eigen::Vector3d::UnitY();
  const double ring = radius * std::cos(phi0);
  const double theta = Reach(ArcHeight(world, target + radius * std::sin(phi0) * up_axis,
                                       ring * Eigen::Vector3d::UnitZ(), ring * Eigen::Vector3d::UnitX()),
                             theta0, theta0 + azimuth, floor);
  const Eigen::Vector3d outward(std::sin(theta), 0, std::cos(theta));
  const double phi = Reach(ArcHeight(world, target, radius * outward, radius * up_axis), phi0, phi1, floor);
  eye = target + radius * (std::cos(phi) * outward + std::sin(phi) * up_axis);
}

// distance => distance / factor, within the zoom's range => no lower than the floor. The eye's
// world height is affine along the line: h(d) = h(now) + (d - now) slope.
void Camera::Zoom(double factor) {
  const Eigen::Vector3d arm = eye - target;
  const double distance = arm.norm();
  if (distance == 0) return;
  double wanted = std::clamp(distance / factor, kMinZoomDistance, kMaxZoomDistance);
  // From outside the range, a zoom in never takes the eye farther, nor a zoom out nearer.
  wanted = factor >= 1 ? std::min(wanted, distance) : std::max(wanted, distance);
  const Eigen::Vector3d direction = arm / distance;
  const double height = EyeHeight(), floor = std::min(kMinEyeHeight, height);
  const double slope = (scene.inverse().linear() * direction).y();
  if (height + (wanted - distance) * slope < floor - kGroundSlack)
    wanted = distance + (floor - height) / slope;
  eye = target + wanted * direction;
}

}  // namespace flagsim::render
