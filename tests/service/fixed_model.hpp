// A scene whose model the user has set: its integrator and grid as they stand, auto choosing
// neither (integrator=rk4 and cols=32 would do the same). For tests of something else that
// compare every parameter's value, or states, across steps in which auto would switch.
#pragma once

#include "server/scene/scene.hpp"

namespace flagsim::testing {

inline Scene FixedModel(Scene scene) {
  scene.model.auto_integrator = false;
  scene.model.auto_grid = false;
  return scene;
}

}  // namespace flagsim::testing
