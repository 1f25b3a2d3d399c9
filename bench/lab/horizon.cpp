// How long two models of the same scene agree point by point: the agreement horizon. Each preset
// from rest, stepped as the server steps it (float, automatic substeps, self-collision), compared
// every 10 ms by the projected gap on the preset's camera (the 95th percentile over the coarser
// model's nodes, the finer grid resampled onto them over the cloth's (u, v)):
//   grids    32 x 24 against 64 x 48, and 64 x 48 against 128 x 96, the same integrator;
//   methods  each integrator at its server substeps against symplectic Euler at an eighth of its
//            substep, on the preset's grid (the reference for the time step's error alone).
// The horizon is the first time the gap passes 1 px (and 10 px); a chaotic flag parts from any
// other model sooner or later, so past its horizon a comparison point by point means nothing and
// only statistics do (lab shape).
#include <cmath>
#include <functional>

#include "bench/lab/experiments.hpp"
#include "bench/lab/table.hpp"
#include "server/model/frame_defect.hpp"
#include "server/sim/resample.hpp"
#include "server/scene/scene_file.hpp"
#include "server/sim/simulation.hpp"

namespace flagsim::lab {
namespace {

constexpr double kDuration = 3.0;  ///< s compared
constexpr double kInterval = 0.01;  ///< s between comparisons

struct Horizon {
  double one_px = INFINITY, ten_px = INFINITY;  ///< s: when the gap first passed them
  double at_half_second = 0;                   ///< px
};

/// Steps `coarse` and `fine` together, comparing them by `gap` every kInterval.
Horizon Compare(sim::Simulation<float>* coarse, sim::Simulation<float>* fine,
                const std::function<double()>& gap) {
  Horizon horizon;
  const double dt = coarse->params().dt;
  const int every = std::max(1, int(std::lround(kInterval / dt)));
  const int steps = int(std::lround(kDuration / dt));
  for (int i = 1; i <= steps; ++i) {
    coarse->Step();
    fine->Step();
    if (i % every != 0) continue;
    const double t = i * dt, px = gap();
    if (px > 1 && !std::isfinite(horizon.one_px)) horizon.one_px = t;
    if (px > 10 && !std::isfinite(horizon.ten_px)) horizon.ten_px = t;
    if (std::abs(t - 0.5) < 0.5 * kInterval) horizon.at_half_second = px;
  }
  return horizon;
}

Scene AtGrid(Scene scene, int cols, int rows) {
  scene.sim.cols = cols;
  scene.sim.rows = rows;
  scene.sim.threads = 1;
  return scene;
}

void AddRow(Table* table, const std::string& preset, const std::string& comparison, const Horizon& h) {
  table->Add({preset, comparison, Table::Number(h.one_px), Table::Number(h.ten_px), Table::Number(h.at_half_second)});
}

}  // namespace

void AgreementHorizon(const std::string& csv) {
  Table table({"scene", "models_compared_point_by_point", "horizon_1px_s", "horizon_10px_s", "gap_at_0.5s_px"}, csv);
  const int grids[3][2] = {{32, 24}, {64, 48}, {128, 96}};
  for (const std::string& preset : PresetNames()) {
    const Scene scene = LoadScene(preset);
    for (int g = 0; g + 1 < 3; ++g) {
      const Scene coarse_scene = AtGrid(scene, grids[g][0], grids[g][1]);
      const Scene fine_scene = AtGrid(scene, grids[g + 1][0], grids[g + 1][1]);
      sim::Simulation<float> coarse(coarse_scene.sim, scene.wind, scene.seed);
      sim::Simulation<float> fine(fine_scene.sim, scene.wind, scene.seed);
      const Horizon horizon = Compare(&coarse, &fine, [&] {
        const sim::ClothState<float> resampled = sim::Resample(fine.model(), fine.state(), coarse.model());
        return model::ScreenGap(scene.camera, coarse.state(), resampled).percentile;
      });
      AddRow(&table, preset,
             std::to_string(grids[g][0]) + "x" + std::to_string(grids[g][1]) + " vs " +
                 std::to_string(grids[g + 1][0]) + "x" + std::to_string(grids[g + 1][1]),
             horizon);
    }
    for (const sim::IntegratorKind kind :
         {sim::IntegratorKind::kSymplecticEuler, sim::IntegratorKind::kVelocityVerlet, sim::IntegratorKind::kRk4,
          sim::IntegratorKind::kXpbd, sim::IntegratorKind::kImplicitEuler, sim::IntegratorKind::kProjectiveDynamics}) {
      Scene run_scene = AtGrid(scene, scene.sim.cols, scene.sim.rows);
      run_scene.sim.integrator = kind;
      Scene reference_scene = AtGrid(scene, scene.sim.cols, scene.sim.rows);
      reference_scene.sim.integrator = sim::IntegratorKind::kSymplecticEuler;
      reference_scene.sim.substeps = 8 * sim::SubstepsFor(reference_scene.sim);
      sim::Simulation<float> run(run_scene.sim, scene.wind, scene.seed);
      sim::Simulation<float> reference(reference_scene.sim, scene.wind, scene.seed);
      const Horizon horizon = Compare(
          &run, &reference, [&] { return model::ScreenGap(scene.camera, run.state(), reference.state()).percentile; });
      AddRow(&table, preset, sim::IntegratorName(kind) + " vs reference", horizon);
    }
  }
}

}  // namespace flagsim::lab
