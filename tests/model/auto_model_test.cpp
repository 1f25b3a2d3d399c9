#include "server/model/auto_model.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "server/scene/scene_file.hpp"

namespace flagsim::model {
namespace {

/// The breeze flown for a second, as a snapshot, and its camera.
struct Flying {
  Scene scene = LoadScene("breeze");
  sim::SimulationSnapshot<float> snapshot;
  Flying() {
    sim::Simulation<float> simulation(scene.sim, scene.wind, scene.seed);
    for (int i = 0; i < 500; ++i) simulation.Step();
    snapshot = simulation.Snapshot();
  }
};

render::Camera Farther(render::Camera camera, double distance) {
  camera.eye = camera.target + distance * (camera.eye - camera.target);
  return camera;
}

// Checked on the model (its estimates and the fitted cost model), not on a clock.
TEST(AutoModel, MeetsTheBudgetAtThePresetsViewAndCostsFarLessTenTimesFarther) {
  const Flying flying;
  AutoSettings settings;
  settings.cost_budget = 1.6;  // two cores
  const ModelDecision near = DecideModel(flying.snapshot, flying.scene.camera, settings);
  const ModelDecision far = DecideModel(flying.snapshot, Farther(flying.scene.camera, 10), settings);
  EXPECT_EQ(near.kind, ChoiceKind::kWithinBudget) << Describe(near);
  EXPECT_LE(near.error_px, settings.budget_px) << Describe(near);
  EXPECT_EQ(far.kind, ChoiceKind::kWithinBudget) << Describe(far);
  EXPECT_LE(far.cols * far.rows, near.cols * near.rows) << Describe(near) << "; " << Describe(far);
  EXPECT_LT(5 * far.cost, near.cost) << Describe(near) << "; " << Describe(far);
  // The same snapshot, the same decision.
  const ModelDecision again = DecideModel(flying.snapshot, flying.scene.camera, settings);
  EXPECT_EQ(Describe(again), Describe(near));
}

TEST(AutoModel, KeepsWhatTheUserFixed) {
  const Flying flying;
  AutoSettings settings;
  settings.grid = false;
  const ModelDecision integrator_only = DecideModel(flying.snapshot, Farther(flying.scene.camera, 10), settings);
  EXPECT_EQ(integrator_only.cols, flying.scene.sim.cols);
  EXPECT_EQ(integrator_only.rows, flying.scene.sim.rows);
  settings.grid = true;
  settings.integrator = false;
  const ModelDecision grid_only = DecideModel(flying.snapshot, Farther(flying.scene.camera, 10), settings);
  EXPECT_EQ(grid_only.integrator, flying.scene.sim.integrator);
  EXPECT_LT(grid_only.cols, flying.scene.sim.cols) << Describe(grid_only);  // a distant flag needs fewer nodes
}

TEST(AutoModel, SaysWhenTheBudgetIsOutOfReachInRealTime) {
  const Flying flying;
  AutoSettings settings;
  settings.budget_px = 0.001;  // a thousandth of a pixel: no grid's cells are that flat
  settings.cost_budget = 0.8;
  const ModelDecision decision = DecideModel(flying.snapshot, flying.scene.camera, settings);
  EXPECT_EQ(decision.kind, ChoiceKind::kMostAccurateInRealTime) << Describe(decision);
  EXPECT_LE(decision.cost, settings.cost_budget);
  EXPECT_GT(decision.error_px, settings.budget_px);
}

}  // namespace
}  // namespace flagsim::model
