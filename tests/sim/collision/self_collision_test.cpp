// Self-collision over whole scenes: no crossing, a step where nothing is near left bit for bit,
// the same states at any thread count; and the independent checker the scenes are judged by.
#include "server/sim/collision/self_collision.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "lab/triangle_crossings.hpp"
#include "server/scene/scene_file.hpp"
#include "server/sim/simulation.hpp"

namespace flagsim::sim {
namespace {

using lab::CrossingTrianglePairs;

TEST(TriangleCrossings, FindTheCrossingOfTwoTrianglesAndNothingInAFlatSheet) {
  const std::vector<std::array<int, 3>> triangles{{0, 1, 2}, {3, 4, 5}};
  std::vector<double> x{0, 1, 0, 0.2, 0.2, 0.2}, y{0, 0, 1, 0.2, 0.3, 0.2}, z{0, 0, 0, -1, 1, 1};
  EXPECT_EQ(CrossingTrianglePairs(triangles, x, y, z), 1);
  z = {0, 0, 0, 0.5, 1, 1};
  EXPECT_EQ(CrossingTrianglePairs(triangles, x, y, z), 0);
  const ClothMesh mesh = BuildClothMesh(8, 6);
  SimParams params;
  params.cols = 8;
  params.rows = 6;
  const ClothModel<float> model = BuildClothModel<float>(params);
  EXPECT_EQ(CrossingTrianglePairs(mesh.triangles, model.rest_x, model.rest_y, model.rest_z), 0);
}

/// Steps the preset for `seconds` and checks every STATE (60 per second): no node in the pole or
/// below the ground, no crossing pair of triangles.
void ExpectNoCrossings(const std::string& preset, double seconds) {
  const Scene scene = LoadScene(preset);
  Simulation<float> simulation(scene.sim, scene.wind, scene.seed);
  const ClothMesh mesh = BuildClothMesh(scene.sim.cols, scene.sim.rows);
  // The hoist edge lies on the pole's surface: at its radius as a float rounds it.
  const double radius = double(float(scene.sim.pole_radius)), top = scene.sim.pole_height;
  const int steps_per_state = int(std::lround(1 / (scene.service.state_rate * scene.sim.dt)));
  int states = 0, worst = 0;
  double nearest_axis = INFINITY, lowest = INFINITY;
  while (simulation.state().time < seconds) {
    for (int i = 0; i < steps_per_state; ++i) simulation.Step();
    const ClothState<float>& state = simulation.state();
    for (int i = 0; i < state.num_nodes(); ++i) {
      if (state.y[i] < top)
        nearest_axis = std::min(nearest_axis, std::hypot(double(state.x[i]), double(state.z[i])));
      lowest = std::min(lowest, double(state.y[i]));
    }
    const int crossings = CrossingTrianglePairs(mesh.triangles, state.x, state.y, state.z);
    worst = std::max(worst, crossings);
    EXPECT_EQ(crossings, 0) << preset << " at " << state.time << " s";
    if (crossings > 0 && ++states > 5) break;  // enough said
  }
  EXPECT_GE(nearest_axis, radius) << preset << ": a node inside the pole";
  EXPECT_GE(lowest, 0.0) << preset << ": a node below the ground";
  EXPECT_EQ(simulation.recoveries(), 0) << preset;
  std::printf("%s: nearest the pole's axis %.4f m (radius %.3f), lowest %.3f m, worst %d crossing pairs\n",
              preset.c_str(), nearest_axis, radius, lowest, worst);
}

TEST(SelfCollision, TheBreezeNeverCrossesItself) { ExpectNoCrossings("breeze", 10); }
TEST(SelfCollision, CalmAirNeverTakesTheFlagIntoThePoleOrThroughItself) { ExpectNoCrossings("calm", 10); }
TEST(SelfCollision, AGaleNeverTakesTheFlagIntoThePoleOrThroughItself) { ExpectNoCrossings("gale", 10); }

TEST(SelfCollision, AStepWhereNothingIsNearIsLeftAsItWasBitForBit) {
  const Scene scene = LoadScene("breeze");
  SimParams without = scene.sim;
  without.self_collision = false;
  Simulation<float> with_collisions(scene.sim, scene.wind, scene.seed),
      plain(without, scene.wind, scene.seed);
  int compared = 0;
  for (; compared < 500; ++compared) {
    with_collisions.Step();
    plain.Step();
    if (with_collisions.self_collision_stats().moved > 0) break;
    ASSERT_EQ(with_collisions.Hash(), plain.Hash()) << "step " << compared;
  }
  EXPECT_GE(compared, 100) << "the breeze touched itself within its first steps";
}

// The threads share the normals, the bounds, the candidates and the detection, the impulses go
// in one order: 1 to 4 threads give the gale's states bit for bit, through steps full of contacts.
TEST(SelfCollision, TheSameStatesAtAnyThreadCount) {
  Scene scene = LoadScene("gale");
  scene.sim.min_nodes_per_thread = 1;  // share even a small flag among the threads
  std::vector<uint64_t> hashes;
  int contacts = 0;
  for (int threads = 1; threads <= 4; ++threads) {
    scene.sim.threads = threads;
    Simulation<float> simulation(scene.sim, scene.wind, scene.seed);
    for (int step = 0; step < 1500; ++step) {
      simulation.Step();
      if (threads == 1) contacts += simulation.self_collision_stats().contacts;
    }
    hashes.push_back(simulation.Hash());
  }
  EXPECT_GT(contacts, 50) << "the gale should have touched itself (78 impulses when written)";
  for (int threads = 2; threads <= 4; ++threads) EXPECT_EQ(hashes[threads - 1], hashes[0]) << threads << " threads";
}

}  // namespace
}  // namespace flagsim::sim
