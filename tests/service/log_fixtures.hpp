// What the tests of logs and replay share: scratch files, and a session whose integrator
// carries state between substeps.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <string>

#include "server/scene/scene.hpp"

namespace flagsim::testing {

/// A path in the test's scratch directory, unique to this process.
inline std::string TempPath(const std::string& name) {
  return std::string(::testing::TempDir()) + "/" + std::to_string(getpid()) + "_" + name;
}

/// A small flag stepped by velocity Verlet, which carries forces from one substep to the next:
/// a checkpoint that failed to carry them, or that changed the run by being taken, shows in
/// the hashes.
/// One thread (replays run on one and two).
inline Scene SmallVerletScene() {
  Scene scene;
  scene.sim.cols = 10;
  scene.sim.rows = 8;
  scene.sim.threads = 1;
  scene.sim.integrator = sim::IntegratorKind::kVelocityVerlet;
  return scene;
}

}  // namespace flagsim::testing
