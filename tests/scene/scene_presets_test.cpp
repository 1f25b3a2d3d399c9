// The presets as flags: what each is meant to show, simulated.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "server/scene/scene_file.hpp"
#include "server/sim/simulation.hpp"

namespace flagsim {
namespace {

// Still air: the flag hangs like cloth, not like a board. After 10 s the whole fly edge (the
// last column) hangs near the pole, within a third of the flag's length of its axis (x = 0,
// z = 0), and below the middle of the hoist; the flag comes to rest and sleeps (within 30 s: how
// soon depends on how its folds slide on each other and on the pole).
TEST(ScenePresets, HangingDrapesNearThePoleWithin10SecondsAndSleeps) {
  const Scene scene = LoadScene("hanging");
  sim::Simulation<float> simulation(scene.sim, scene.wind, scene.seed);
  const int steps = static_cast<int>(std::lround(10.0 / scene.sim.dt));
  for (int i = 0; i < steps; ++i) simulation.Step();
  const sim::ClothModel<float>& model = simulation.model();
  const sim::ClothState<float>& state = simulation.state();
  const double hoist_middle =
      (model.rest_y[model.index(0, 0)] + model.rest_y[model.index(model.rows - 1, 0)]) / 2;
  for (int r = 0; r < model.rows; ++r) {
    const int fly = model.index(r, model.cols - 1);
    EXPECT_LT(std::hypot(state.x[fly], state.z[fly]), scene.sim.width / 3) << "row " << r;
    EXPECT_LT(state.y[fly], hoist_middle) << "row " << r;
  }
  for (int i = 0; i < 2 * steps && !simulation.sleeping(); ++i) simulation.Step();
  EXPECT_TRUE(simulation.sleeping());
  EXPECT_EQ(simulation.recoveries(), 0);
}

}  // namespace
}  // namespace flagsim
