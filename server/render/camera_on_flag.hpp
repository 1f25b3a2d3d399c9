// Camera moves that know where the flag is: zoom toward the point under a pixel, never through
// the flag's near side, and frame the flag.
//
//   ray       through pixel (px, py): the pixel unprojected at the near and far planes with
//             (Projection View)^-1, world points a and b; the ray a + s (b - a), s >= 0
//   hit       the nearest point where the ray meets one of the flag's triangles
//             (Moller and Trumbore 1997)
//   zoom at   P = the hit, else the ray's point at the target's depth. Eye and target each go to
//             P + (X - P) / factor, so P stays under the pixel; the factor is held so that the
//             eye stays kFlagClearance short of the hit (without a hit, no nearer to P than
//             the flag's size), the eye-target distance within Camera's zoom range and the eye
//             above the ground
//   zoom      Camera::Zoom toward the target, held kFlagClearance short of the flag where the line
//             of sight meets it
//   frame     the target to the centre of the flag's bounding box; the eye back along the
//             present line of sight until the box's bounding sphere fills kFrameFill of the
//             narrower field of view
//
// Points are taken in the camera's own frame (eye and target live there): the flag's nodes go
// through `scene`, the seed's transforms of the world, first.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "server/render/camera.hpp"
#include "server/render/camera_moves.hpp"

namespace flagsim::render {

/// The flag's nodes, world frame, node (r, c) at index r cols + c.
struct FlagSurface {
  std::vector<Eigen::Vector3d> nodes;
  int cols = 0, rows = 0;
};

inline constexpr double kFlagClearance = 0.05;  ///< m: the nearest a zoom takes the eye to the flag
inline constexpr double kFrameFill = 0.8;       ///< of the narrower field of view the framed flag spans

/// The nearest point of `flag` seen through pixel (px, py) of `camera`, in the camera's frame;
/// none if that pixel shows no flag.
std::optional<Eigen::Vector3d> FlagUnderPixel(const Camera& camera, const FlagSurface& flag, double px, double py);

/// Whether `operation` needs to know where the flag is: kZoom, kZoomAt, kFrame.
inline bool AimsAtTheFlag(int operation) {
  return operation == CameraMove::kZoom || operation == CameraMove::kZoomAt || operation == CameraMove::kFrame;
}

/// Applies kZoom, kZoomAt or kFrame to `camera` as above (any other move as ApplyCameraMove
/// does); "" or the reason (then `camera` is unchanged).
std::string ApplyFlagCameraMove(const CameraMove& move, const FlagSurface& flag, Camera* camera);

}  // namespace flagsim::render
