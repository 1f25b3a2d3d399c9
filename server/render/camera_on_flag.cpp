#include "server/render/camera_on_flag.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

namespace flagsim::render {
namespace {

/// A ray in the camera's frame: origin + s direction, s >= 0, direction of unit length.
struct Ray {
  Eigen::Vector3d origin, direction;
};

/// The flag's nodes in the camera's frame (through `scene`).
std::vector<Eigen::Vector3d> NodesSeen(const Camera& camera, const FlagSurface& flag) {
  std::vector<Eigen::Vector3d> nodes;
  nodes.reserve(flag.nodes.size());
  for (const Eigen::Vector3d& node : flag.nodes) nodes.push_back(camera.scene * node);
  return nodes;
}

/// The ray from the eye through pixel (px, py), px right and py down from the top left corner:
/// the pixel's normalised device coordinates scaled by the field of view along the camera's
/// right and up axes.
Ray PixelRay(const Camera& camera, double px, double py) {
  const Eigen::Vector3d forward = (camera.target - camera.eye).normalized();
  const Eigen::Vector3d right = forward.cross(camera.up).normalized();
  const Eigen::Vector3d up = right.cross(forward);
  const double half_height = std::tan(camera.fov_y / 2), half_width = half_height * camera.width / camera.height;
  const double x = 2 * px / camera.width - 1, y = 1 - 2 * py / camera.height;
  return {camera.eye, (forward + x * half_width * right + y * half_height * up).normalized()};
}

/// s at which `ray` meets triangle (a, b, c), Moller and Trumbore (1997); none if it misses.
std::optional<double> MeetTriangle(const Ray& ray, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                   const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, p = ray.direction.cross(ac);
  const double det = ab.dot(p);
  if (std::abs(det) < 1e-15) return std::nullopt;  // parallel to the triangle
  const Eigen::Vector3d t = ray.origin - a;
  const double u = t.dot(p) / det;
  if (u < 0 || u > 1) return std::nullopt;
  const Eigen::Vector3d q = t.cross(ab);
  const double v = ray.direction.dot(q) / det;
  if (v < 0 || u + v > 1) return std::nullopt;
  const double s = ac.dot(q) / det;
  return s >= 0 ? std::optional<double>(s) : std::nullopt;
}

/// The least s at which `ray` meets the flag (two triangles a cell); none if it misses.
std::optional<double> NearestHit(const Ray& ray, const std::vector<Eigen::Vector3d>& nodes, int cols, int rows) {
  std::optional<double> nearest;
  const auto node = [&](int r, int c) -> const Eigen::Vector3d& { return nodes[size_t(r) * cols + c]; };
  for (int r = 0; r + 1 < rows; ++r) {
    for (int c = 0; c + 1 < cols; ++c) {
      for (const auto& s : {MeetTriangle(ray, node(r, c), node(r, c + 1), node(r + 1, c + 1)),
                            MeetTriangle(ray, node(r, c), node(r + 1, c + 1), node(r + 1, c))}) {
        if (s && (!nearest || *s < *nearest)) nearest = s;
      }
    }
  }
  return nearest;
}

/// The largest zoom factor (of `wanted`) that leaves the eye kFlagClearance short of a point
/// `reach` ahead of it along its path: the eye moves (1 - 1 / factor) of `path` towards it.
double HoldShort(double wanted, double path, std::optional<double> reach) {
  if (wanted <= 1 || !reach) return wanted;
  const double room = *reach - kFlagClearance;  // how far the eye may go
  if (room <= 0) return 1;                      // at the flag already: no nearer
  return std::min(wanted, room >= path ? wanted : 1 / (1 - room / path));
}

/// Half the diagonal of the flag's bounding box, m (in the camera's frame).
double FlagRadius(const std::vector<Eigen::Vector3d>& nodes) {
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& node : nodes) box.extend(node);
  return nodes.empty() ? 0 : box.diagonal().norm() / 2;
}

/// kZoomAt: eye and target toward the point under the pixel.
std::string ZoomAt(const CameraMove& move, const FlagSurface& flag, Camera* moved) {
  if (move.vector.x() > moved->width || move.vector.y() > moved->height) {
    return "vector: pixel (" + std::to_string(int(move.vector.x())) + ", " + std::to_string(int(move.vector.y())) +
           ") is outside the " + std::to_string(moved->width) + " x " + std::to_string(moved->height) +
           " px picture";
  }
  const Ray ray = PixelRay(*moved, move.vector.x(), move.vector.y());
  const std::vector<Eigen::Vector3d> nodes = NodesSeen(*moved, flag);
  const std::optional<double> hit = NearestHit(ray, nodes, flag.cols, flag.rows);
  const Eigen::Vector3d forward = (moved->target - moved->eye).normalized();
  const double depth = hit ? *hit : (moved->target - moved->eye).dot(forward) / ray.direction.dot(forward);
  const Eigen::Vector3d point = ray.origin + depth * ray.direction;
  const double distance = (moved->target - moved->eye).norm();
  // Toward the flag: up to kFlagClearance short of it. Toward empty air: no nearer to the point
  // than the flag's size, so that zooming on the sky beside the flag never loses it from view.
  double factor = HoldShort(move.factor, depth, hit ? hit : std::optional<double>(depth - FlagRadius(nodes) + kFlagClearance));
  factor = std::clamp(factor, distance / Camera::kMaxZoomDistance, std::max(1.0, distance / Camera::kMinZoomDistance));
  moved->eye = point + (moved->eye - point) / factor;
  moved->target = point + (moved->target - point) / factor;
  return "";
}

/// kZoom: Camera::Zoom, held short of the flag on the line of sight.
void ZoomToTarget(const CameraMove& move, const FlagSurface& flag, Camera* moved) {
  const Eigen::Vector3d arm = moved->target - moved->eye;
  const Ray sight{moved->eye, arm.normalized()};
  const std::optional<double> hit = NearestHit(sight, NodesSeen(*moved, flag), flag.cols, flag.rows);
  // Camera::Zoom moves the eye (1 - 1 / factor) of the eye-target distance along the sight.
  moved->Zoom(HoldShort(move.factor, arm.norm(), hit));
}

/// kFrame: the flag's bounding sphere in the middle of the picture, the line of sight kept.
std::string Frame(const FlagSurface& flag, Camera* moved) {
  const std::vector<Eigen::Vector3d> nodes = NodesSeen(*moved, flag);
  if (nodes.empty()) return "operation: FRAME needs a flag, and there is none";
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& node : nodes) box.extend(node);
  const double radius = std::max(box.diagonal().norm() / 2, 0.1);
  const double half_fov = std::min(moved->fov_y, 2 * std::atan(std::tan(moved->fov_y / 2) * moved->width / moved->height)) / 2;
  const double distance = radius / std::sin(kFrameFill * half_fov);
  const Eigen::Vector3d forward = (moved->target - moved->eye).normalized();
  moved->target = box.center();
  moved->eye = moved->target - distance * forward;
  return "";
}

}  // namespace

std::optional<Eigen::Vector3d> FlagUnderPixel(const Camera& camera, const FlagSurface& flag, double px, double py) {
  const Ray ray = PixelRay(camera, px, py);
  const std::optional<double> hit = NearestHit(ray, NodesSeen(camera, flag), flag.cols, flag.rows);
  if (!hit) return std::nullopt;
  return ray.origin + *hit * ray.direction;
}

std::string ApplyFlagCameraMove(const CameraMove& move, const FlagSurface& flag, Camera* camera) {
  std::string problem = CheckCameraMove(move);
  if (!problem.empty()) return problem;
  Camera moved = *camera;
  switch (move.operation) {
    case CameraMove::kZoom:
      ZoomToTarget(move, flag, &moved);
      break;
    case CameraMove::kZoomAt:
      problem = ZoomAt(move, flag, &moved);
      break;
    case CameraMove::kFrame:
      problem = Frame(flag, &moved);
      break;
    default:
      return ApplyCameraMove(move, camera);
  }
  if (problem.empty()) problem = CheckMovedCamera(move.operation, *camera, moved);
  if (problem.empty()) *camera = moved;
  return problem;
}

}  // namespace flagsim::render
