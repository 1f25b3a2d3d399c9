// CAMERA commands as the renderer sees them: one validated move of the camera.
#pragma once

#include <Eigen/Core>
#include <string>

#include "server/render/camera.hpp"

namespace flagsim::render {

struct CameraMove {
  enum Operation {
    kRotateX = 1,
    kRotateY,
    kRotateZ,
    kTranslate,
    kScale,
    kOrbit,
    kLookAt,
    kSetImageSize,
    kReset,
    kZoom,
    kSetEye,
    kSetFov,
    kFrame,  ///< the flag in the middle of the picture (camera_on_flag.hpp)
    kZoomAt  ///< zoom by `factor` toward what pixel (vector.x, vector.y) shows (camera_on_flag.hpp)
  };
  int operation = 0;
  double angle = 0;                                  ///< rad: rotations; orbit azimuth; field of view
  double angle2 = 0;                                 ///< rad: orbit elevation
  Eigen::Vector3d vector = Eigen::Vector3d::Zero();  ///< m: translation, scale centre, look-at point, eye
  double factor = 1;                                 ///< scale; zoom (2: half the distance)
  int width = 0, height = 0;                         ///< px, image size

  static constexpr double kMaxAngle = 6.283185307179586;  ///< rad, one turn
  static constexpr double kMaxDistance = 1000;            ///< m
  static constexpr double kMinFactor = 0.01, kMaxFactor = 100;
  static constexpr double kMinFov = 10, kMaxFov = 120;  ///< degrees, vertical field of view
  static constexpr int kMinSize = 16, kMaxWidth = 3840, kMaxHeight = 2160;  ///< px
};

/// Whether the move's fields are valid for its operation: "" or the reason naming the field
/// and what is allowed.
std::string CheckCameraMove(const CameraMove& move);

/// Whether `moved` (made by `operation` from `before`) may be taken: its view defined, its eye
/// above the ground (or no lower than it was); "" or the reason.
std::string CheckMovedCamera(int operation, const Camera& before, const Camera& moved);

/// Applies `move` to `camera` if it is valid; returns "" or the reason naming the field and
/// what is allowed (then `camera` is unchanged). kReset, kFrame and kZoomAt are the caller's: it
/// knows the scene and the flag.
/// A move may not put the eye below Camera::kMinEyeHeight above the ground (nor lower it if it
/// is there already): orbit and zoom stop at the ground, the other moves are rejected.
std::string ApplyCameraMove(const CameraMove& move, Camera* camera);

}  // namespace flagsim::render
