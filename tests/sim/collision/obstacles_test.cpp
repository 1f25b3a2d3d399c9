// The pole and the ground, as a flag meets them.
#include "server/sim/collision/obstacles.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "server/scene/scene_file.hpp"
#include "server/sim/simulation.hpp"

namespace flagsim::sim {
namespace {

TEST(Obstacles, AFlagOnAShortPoleInStillAirEndsUpOnTheGroundAndLiesThere) {
  Scene scene = LoadScene("hanging");
  scene.sim.pole_height = 1.2;  // the flag's foot 0.18 m above the ground, its fly 1.5 m long
  Simulation<float> simulation(scene.sim, scene.wind, scene.seed);
  double lowest = INFINITY;
  while (simulation.state().time < 10) {
    simulation.Step();
    for (float y : simulation.state().y) lowest = std::min(lowest, double(y));
  }
  EXPECT_GE(lowest, 0.0);
  int resting = 0;  // nodes on the ground at the end
  for (float y : simulation.state().y) resting += y <= scene.sim.thickness;
  EXPECT_GT(resting, 0);
  std::printf("on a %.1f m pole: %d nodes rest on the ground, lowest %.4f m\n", scene.sim.pole_height,
              resting, lowest);
}

}  // namespace
}  // namespace flagsim::sim
