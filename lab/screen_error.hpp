// Errors as the viewer sees them: node positions projected through a camera to pixels.
#pragma once

#include "server/render/camera.hpp"
#include "server/sim/cloth_state.hpp"

namespace flagsim::lab {

struct ScreenError {
  double rms = 0;      ///< px, root mean square over nodes
  double largest = 0;  ///< px, the worst node
};

/// How far apart the nodes of a and b land on the camera's image. Nodes behind the camera
/// count as infinitely far.
ScreenError ScreenDistance(const render::Camera& camera, const sim::ClothState<double>& a,
                           const sim::ClothState<double>& b);

}  // namespace flagsim::lab
