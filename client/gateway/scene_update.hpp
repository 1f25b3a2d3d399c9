// A STATE as a foxglove.SceneUpdate: the cloth as one triangle list (two triangles per grid
// cell, indexed) and the pole as a cylinder, so a 3D panel shows the flag from any side,
// independent of the server's camera.
//
// Foxglove's world is z up; the simulation's is y up. Points are turned by
//   (x, y, z)_sim -> (x, -z, y)_foxglove
// a rotation (determinant +1), so the cloth's winding and the scene's handedness are kept.
#pragma once

#include <string>

#include "flagsim/state_t.hpp"

namespace flagsim::gateway {

/// The JSON text of a foxglove.SceneUpdate for `state`: entities "flag" and "pole" in frame
/// "world"; empty if the state's grid does not match its positions.
std::string SceneUpdateJson(const state_t& state);

}  // namespace flagsim::gateway
