// Clipping triangles in homogeneous clip space (before the divide by w), Sutherland-Hodgman
// against the near and far planes and a guard band around the view: -w <= z <= w and
// |x|, |y| <= kGuardBand w. Inside the guard band the rasterizer's fixed-point arithmetic
// cannot overflow, and triangles that merely cross the screen's edges need no clipping.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace flagsim::render {

constexpr float kGuardBand = 4.0f;  ///< in units of the half-screen: x_ndc, y_ndc in [-4, 4]
constexpr int kClipChannels = 16;   ///< attributes carried through clipping

/// A vertex after the vertex stage: where it is in clip space, and what may be interpolated.
struct ClipVertex {
  Eigen::Vector4f clip;                ///< clip-space position (x, y, z, w)
  float channels[kClipChannels] = {};  ///< attributes, interpolated linearly in clip space
};

/// Where a triangle stands against the clip volume.
enum class ClipTest { kInside, kOutside, kCrossing };
ClipTest ClassifyTriangle(const ClipVertex& a, const ClipVertex& b, const ClipVertex& c);

/// Clips triangle (a, b, c) and appends the resulting polygon's fan of triangles to `out`
/// (three vertices per triangle, orientation kept). Each intersection is computed from the
/// inside vertex towards the outside one, so two triangles sharing an edge get the same point.
void ClipTriangle(const ClipVertex& a, const ClipVertex& b, const ClipVertex& c,
                  std::vector<ClipVertex>* out);

/// Clips the segment a-b to the same volume (parametric, Liang-Barsky in clip space); false if
/// nothing of it is left.
bool ClipLine(Eigen::Vector4f* a, Eigen::Vector4f* b);

}  // namespace flagsim::render
