#include "server/render/camera_moves.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace flagsim::render {
namespace {

constexpr double kGroundSlack = 1e-9;  ///< m below the floor a move may end by rounding

std::string Number(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%g", value);
  return text;
}

std::string CheckRange(const char* field, double value, double low, double high, const char* unit) {
  if (std::isfinite(value) && value >= low && value <= high) return "";
  return std::string(field) + ": " + Number(value) + " is " +
         (std::isfinite(value) ? "out of range" : "not finite") + "; allowed " + Number(low) + " .. " +
         Number(high) + " " + unit;
}

std::string CheckVector(const Eigen::Vector3d& vector) {
  const char* names[3] = {"vector.x", "vector.y", "vector.z"};
  for (int k = 0; k < 3; ++k) {
    std::string problem =
        CheckRange(names[k], vector[k], -CameraMove::kMaxDistance, CameraMove::kMaxDistance, "m");
    if (!problem.empty()) return problem;
  }
  return "";
}

/// A field of view given in rad, reported in degrees (flagctl takes degrees).
std::string CheckFov(double radians) {
  // Compared in rad, as flagctl converts (degrees * pi / 180), so that the limits themselves pass.
  if (radians >= CameraMove::kMinFov * M_PI / 180 && radians <= CameraMove::kMaxFov * M_PI / 180) return "";
  const double degrees = radians * 180 / M_PI;
  return "angle: " + Number(degrees) + " degrees is " +
         (std::isfinite(degrees) ? "out of range" : "not finite") + "; allowed " +
         Number(CameraMove::kMinFov) + " .. " + Number(CameraMove::kMaxFov) +
         " degrees of vertical field of view";
}

/// An angle given in rad, reported in degrees (flagctl and the live view take degrees).
std::string CheckAngle(const char* field, double radians) {
  if (std::isfinite(radians) && std::abs(radians) <= CameraMove::kMaxAngle) return "";
  const double degrees = radians * 180 / M_PI, limit = CameraMove::kMaxAngle * 180 / M_PI;
  return std::string(field) + ": " + Number(degrees) + " degrees is " +
         (std::isfinite(degrees) ? "out of range" : "not finite") + "; allowed " + Number(-limit) + " .. " +
         Number(limit) + " degrees";
}

/// The field whose value moves the eye in `operation`, for a reason that names it.
const char* FieldMovingTheEye(int operation) {
  switch (operation) {
    case CameraMove::kRotateX:
    case CameraMove::kRotateY:
    case CameraMove::kRotateZ:
    case CameraMove::kOrbit:
      return "angle";
    case CameraMove::kScale:
    case CameraMove::kZoom:
    case CameraMove::kZoomAt:
      return "factor";
    case CameraMove::kFrame:
      return "operation";
    default:
      return "vector";
  }
}

}  // namespace

std::string CheckCameraMove(const CameraMove& m) {
  using M = CameraMove;
  switch (m.operation) {
    case M::kRotateX:
    case M::kRotateY:
    case M::kRotateZ:
      return CheckAngle("angle", m.angle);
    case M::kOrbit: {
      const std::string problem = CheckAngle("angle", m.angle);
      return problem.empty() ? CheckAngle("angle2", m.angle2) : problem;
    }
    case M::kTranslate:
    case M::kLookAt:
    case M::kSetEye:
      return CheckVector(m.vector);
    case M::kZoom:
      return CheckRange("factor", m.factor, M::kMinFactor, M::kMaxFactor, "");
    case M::kSetFov:
      return CheckFov(m.angle);
    case M::kScale: {
      const std::string problem = CheckRange("factor", m.factor, M::kMinFactor, M::kMaxFactor, "");
      return problem.empty() ? CheckVector(m.vector) : problem;
    }
    case M::kSetImageSize: {
      const std::string problem = CheckRange("width", m.width, M::kMinSize, M::kMaxWidth, "px");
      return problem.empty() ? CheckRange("height", m.height, M::kMinSize, M::kMaxHeight, "px") : problem;
    }
    case M::kZoomAt: {
      const std::string problem = CheckRange("factor", m.factor, M::kMinFactor, M::kMaxFactor, "");
      if (!problem.empty()) return problem;
      const std::string x = CheckRange("vector.x", m.vector.x(), 0, M::kMaxWidth, "px (the pixel's column)");
      return x.empty() ? CheckRange("vector.y", m.vector.y(), 0, M::kMaxHeight, "px (the pixel's row)") : x;
    }
    case M::kReset:
    case M::kFrame:
      return "";
    default:
      return "operation: " + std::to_string(m.operation) +
             " is not one; allowed 1 .. 14 (ROTATE_X, ROTATE_Y, ROTATE_Z, TRANSLATE, SCALE, ORBIT, LOOK_AT, "
             "SET_IMAGE_SIZE, RESET, ZOOM, SET_EYE, SET_FOV, FRAME, ZOOM_AT)";
  }
}

std::string CheckMovedCamera(int operation, const Camera& before, const Camera& moved) {
  // The view must stay defined: an eye away from its target, not looking straight up or down.
  const Eigen::Vector3d forward = moved.target - moved.eye;
  if (!(forward.norm() >= 1e-3) || !(forward.normalized().cross(moved.up).norm() >= 1e-6)) {
    return "vector: the camera would look at its own position or straight along its up axis";
  }
  // The eye stays above the ground, or no lower than it was if it was below already. Orbit and
  // zoom stop there themselves; kGroundSlack forgives their rounding.
  const double height = moved.EyeHeight(), floor = std::min(Camera::kMinEyeHeight, before.EyeHeight());
  if (!(height >= floor - kGroundSlack)) {
    const std::string allowed = floor < Camera::kMinEyeHeight
                                    ? Number(floor) + " m (no lower than the eye is now)"
                                    : Number(Camera::kMinEyeHeight) + " m above the ground";
    return std::string(FieldMovingTheEye(operation)) + ": the eye would be at y = " + Number(height) +
           " m in the world, " + (height < 0 ? "under" : "too near") +
           " the ground (y = 0); allowed at least " + allowed + "; the camera is unchanged";
  }
  return "";
}

std::string ApplyCameraMove(const CameraMove& move, Camera* camera) {
  std::string problem = CheckCameraMove(move);
  if (!problem.empty()) return problem;
  Camera moved = *camera;
  switch (move.operation) {
    case CameraMove::kRotateX:
      moved.RotateScene(Eigen::Vector3d::UnitX(), move.angle);
      break;
    case CameraMove::kRotateY:
      moved.RotateScene(Eigen::Vector3d::UnitY(), move.angle);
      break;
    case CameraMove::kRotateZ:
      moved.RotateScene(Eigen::Vector3d::UnitZ(), move.angle);
      break;
    case CameraMove::kTranslate:
      moved.Translate(move.vector);
      break;
    case CameraMove::kScale:
      moved.ScaleScene(move.factor, move.vector);
      break;
    case CameraMove::kOrbit:
      moved.Orbit(move.angle, move.angle2);
      break;
    case CameraMove::kLookAt:
      moved.LookAt(move.vector);
      break;
    case CameraMove::kSetImageSize:
      moved.width = move.width;
      moved.height = move.height;
      break;
    case CameraMove::kZoom:
      moved.Zoom(move.factor);
      break;
    case CameraMove::kSetEye:
      moved.eye = move.vector;
      break;
    case CameraMove::kSetFov:
      moved.fov_y = move.angle;
      break;
    default:
      return "operation: RESET, FRAME and ZOOM_AT are the session's to apply (it knows the scene and the flag)";
  }
  problem = CheckMovedCamera(move.operation, *camera, moved);
  if (problem.empty()) *camera = moved;
  return problem;
}

}  // namespace flagsim::render
