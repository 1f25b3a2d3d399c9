// The camera: a perspective view of the world, moved with the seed's affine transforms.
//
//   clip = Projection() * View() * world,   View() = LookAt(eye, target, up) * scene
//
// `scene` accumulates the seed's moves of the world in front of the camera (rotations about
// the target, scaling about a point); translation, orbit and zoom move the camera itself. Lighting
// is computed in world space, so lights stay with the flag when the scene is turned.
//
// The ground is the plane y = 0 of the world. Orbit and zoom stop the eye at kMinEyeHeight above
// it (at its own height if it is lower already: they never take it further down); the other
// moves are checked by ApplyCameraMove (camera_moves.hpp).
#pragma once

#include <Eigen/Geometry>

namespace flagsim::render {

struct Camera {
  Eigen::Vector3d eye{2.6, 1.9, 4.4};                   ///< m, world frame
  Eigen::Vector3d target{0.8, 2.2, 0.0};                ///< m, the point looked at
  Eigen::Vector3d up{0, 1, 0};                          ///< world up
  double fov_y = 0.70;                                  ///< rad, vertical field of view (about 40 degrees)
  double near_plane = 0.05;                             ///< m
  double far_plane = 100.0;                             ///< m
  int width = 1280;                                     ///< px
  int height = 720;                                     ///< px
  Eigen::Affine3d scene = Eigen::Affine3d::Identity();  ///< the seed's transforms of the world

  static constexpr double kMinEyeHeight = 0.05;    ///< m: the eye's least height above the ground
  static constexpr double kMinZoomDistance = 0.1;  ///< m from eye to target: the nearest a zoom goes
  static constexpr double kMaxZoomDistance = 200;  ///< m from eye to target: the farthest a zoom goes

  Eigen::Matrix4d View() const;        ///< world -> camera (camera looks down -z)
  Eigen::Matrix4d Projection() const;  ///< camera -> clip, OpenGL convention (z in [-w, w])
  /// The eye in world coordinates (undoing `scene`), for lighting and the ground.
  Eigen::Vector3d EyeInWorld() const { return scene.inverse() * eye; }
  /// m: the eye's height above the ground, y of EyeInWorld().
  double EyeHeight() const { return EyeInWorld().y(); }

  // The moves CAMERA commands make.
  void RotateScene(const Eigen::Vector3d& axis, double angle);  ///< about the target
  void ScaleScene(double factor, const Eigen::Vector3d& centre);
  void Translate(const Eigen::Vector3d& offset);  ///< eye and target together
  /// The eye around the target by azimuth, then elevation (rad), stopping at the ground.
  void Orbit(double azimuth, double elevation);
  /// The eye along the line to the target: its distance divided by `factor` (> 0), kept within
  /// [kMinZoomDistance, kMaxZoomDistance] and stopping at the ground.
  void Zoom(double factor);
  void LookAt(const Eigen::Vector3d& point) { target = point; }
};

/// Where world point (x, y, z) lands on `camera`'s image, px (x right, y down), given
/// clip_from_world = Projection() * View(); false if it is behind the eye.
inline bool ToPixel(const Eigen::Matrix4d& clip_from_world, const Camera& camera, double x, double y, double z,
                    Eigen::Vector2d* pixel) {
  const Eigen::Vector4d clip = clip_from_world * Eigen::Vector4d(x, y, z, 1.0);
  if (clip.w() <= 0) return false;
  *pixel = Eigen::Vector2d((clip.x() / clip.w() + 1) * 0.5 * camera.width,
                           (1 - clip.y() / clip.w()) * 0.5 * camera.height);
  return true;
}

}  // namespace flagsim::render
