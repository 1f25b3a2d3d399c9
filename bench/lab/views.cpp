// What each view needs: for every preset, at its own camera, 3 and 10 times farther, and at two
// image sizes, the screen_error of each grid from 16 x 12 to 128 x 96 (server/model): the
// frame-interval defect of symplectic Euler at the server's substeps (time) and the sagitta of
// the grid's cells (resolution), with the CPU a step costs on one thread. Each grid flies 2 s
// from rest first; the views share the states. The cheapest grid within 1 px per view is what
// `auto` should choose for the grid; how much cheaper a far view is than the preset's own is the
// saving (Koh et al. 2014 report 5x and 9x for view-dependent refinement).
#include <cmath>
#include <map>

#include "bench/lab/experiments.hpp"
#include "bench/lab/table.hpp"
#include "lab/cpu_time.hpp"
#include "server/model/frame_defect.hpp"
#include "server/model/resolution_error.hpp"
#include "server/scene/scene_file.hpp"
#include "server/sim/simulation.hpp"

namespace flagsim::lab {
namespace {

constexpr double kFlySeconds = 2.0;
constexpr double kBudgetPx = 1.0;

/// The preset's camera moved back along its line of sight, `distance` times as far from the target.
render::Camera Farther(render::Camera camera, double distance, int width, int height) {
  camera.eye = camera.target + distance * (camera.eye - camera.target);
  camera.width = width;
  camera.height = height;
  return camera;
}

}  // namespace

void Views(const std::string& csv) {
  Table table({"scene", "distance", "image", "grid", "resolution_px", "time_px", "screen_error_px",
               "ms_per_step", "cheapest_within_1px"},
              csv);
  const int grids[][2] = {{16, 12}, {24, 18}, {32, 24}, {48, 36}, {64, 48}, {96, 72}, {128, 96}};
  const int images[][2] = {{1280, 720}, {640, 360}};
  for (const std::string& preset : PresetNames()) {
    const Scene scene = LoadScene(preset);
    std::map<int, sim::SimulationSnapshot<float>> snapshots;
    std::map<int, double> cost;
    std::map<int, sim::ClothModel<float>> models;
    for (int g = 0; g < 7; ++g) {
      sim::SimParams params = scene.sim;
      params.cols = grids[g][0];
      params.rows = grids[g][1];
      params.threads = 1;
      sim::Simulation<float> simulation(params, scene.wind, scene.seed);
      const int steps = int(std::lround(kFlySeconds / params.dt));
      const double start = ThreadCpuSeconds();
      for (int i = 0; i < steps; ++i) simulation.Step();
      cost[g] = 1e3 * (ThreadCpuSeconds() - start) / steps;
      snapshots.emplace(g, simulation.Snapshot());
      models.emplace(g, simulation.model());
    }
    const int frame_steps = std::max(1, int(std::lround(1.0 / (scene.service.frame_rate * scene.sim.dt))));
    for (const double distance : {1.0, 3.0, 10.0}) {
      for (const auto& image : images) {
        const render::Camera camera = Farther(scene.camera, distance, image[0], image[1]);
        std::vector<std::vector<std::string>> rows;
        int cheapest = -1;
        for (int g = 0; g < 7; ++g) {
          const model::ClothOnScreen cloth = model::MeasureClothOnScreen(models.at(g), snapshots.at(g).state, camera);
          const double resolution =
              model::ResolutionErrorPx(cloth, scene.sim.width, scene.sim.height, grids[g][0], grids[g][1]);
          const double time = model::MeasureFrameDefect(snapshots.at(g), camera, frame_steps).error_px;
          if (cheapest < 0 && resolution + time <= kBudgetPx) cheapest = g;
          rows.push_back({preset, Table::Number(distance), std::to_string(image[0]) + "x" + std::to_string(image[1]),
                          std::to_string(grids[g][0]) + "x" + std::to_string(grids[g][1]), Table::Number(resolution),
                          Table::Number(time), Table::Number(resolution + time), Table::Number(cost[g]), ""});
        }
        if (cheapest >= 0) rows[cheapest].back() = "yes";
        for (const auto& row : rows) table.Add(row);
      }
    }
  }
}

}  // namespace flagsim::lab
