#include "camera_moves.hpp"

#include <cmath>
#include <cstdio>

namespace flagsim::render {
namespace {

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

/// Checks the move's fields for its operation; "" if it may be applied.
std::string Check(const CameraMove& m) {
  using M = CameraMove;
  switch (m.operation) {
    case M::kRotateX:
    case M::kRotateY:
    case M::kRotateZ:
      return CheckRange("angle", m.angle, -M::kMaxAngle, M::kMaxAngle, "rad");
    case M::kOrbit: {
      const std::string problem = CheckRange("angle", m.angle, -M::kMaxAngle, M::kMaxAngle, "rad");
      return problem.empty() ? CheckRange("angle2", m.angle2, -M::kMaxAngle, M::kMaxAngle, "rad") : problem;
    }
    case M::kTranslate:
    case M::kLookAt:
      return CheckVector(m.vector);
    case M::kScale: {
      const std::string problem = CheckRange("factor", m.factor, M::kMinFactor, M::kMaxFactor, "");
      return problem.empty() ? CheckVector(m.vector) : problem;
    }
    case M::kSetImageSize: {
      const std::string problem = CheckRange("width", m.width, M::kMinSize, M::kMaxWidth, "px");
      return problem.empty() ? CheckRange("height", m.height, M::kMinSize, M::kMaxHeight, "px") : problem;
    }
    default:
      return "operation: " + std::to_string(m.operation) +
             " is not one; allowed 1 .. 9 (ROTATE_X, ROTATE_Y, ROTATE_Z, TRANSLATE, SCALE, ORBIT, LOOK_AT, "
             "SET_IMAGE_SIZE, RESET)";
  }
}

}  // namespace

std::string ApplyCameraMove(const CameraMove& move, Camera* camera) {
  std::string problem = Check(move);
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
    default:
      return "operation: RESET is the session's to apply";
  }
  // The view must stay defined: an eye away from its target, not looking straight up or down.
  const Eigen::Vector3d forward = moved.target - moved.eye;
  if (forward.norm() < 1e-3 || forward.normalized().cross(moved.up).norm() < 1e-6) {
    return "vector: the camera would look at its own position or straight along its up axis";
  }
  *camera = moved;
  return "";
}

}  // namespace flagsim::render
