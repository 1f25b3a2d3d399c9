// What `auto` chooses (server/model/auto_model.hpp) for each preset at its own camera, 3 and 10
// times farther, at 1280 x 720 and 640 x 360, with a cost budget of one core: the model, its
// estimated screen_error and cost; then the flag switched to that model (Simulation::Regrid and
// the integrator) and flown another second, and its screen_error measured there (the frame
// defect and the resolution error of the state it reached); beside the preset's own model
// (32 x 24, symplectic Euler) measured at the same view.
#include <cmath>

#include "bench/lab/experiments.hpp"
#include "bench/lab/table.hpp"
#include "server/model/auto_model.hpp"
#include "server/model/frame_defect.hpp"
#include "server/model/resolution_error.hpp"
#include "server/scene/scene_file.hpp"

namespace flagsim::lab {
namespace {

constexpr double kFirstSeconds = 1.0, kAfterSeconds = 1.0;

/// screen_error of a simulation's present state at `camera`: frame defect and resolution, px.
struct Measured {
  double time = 0, resolution = 0;
  double total() const { return time + resolution; }
};
Measured MeasuredError(const sim::Simulation<float>& simulation, const render::Camera& camera) {
  const int frame_steps = std::max(1, int(std::lround(1.0 / (30.0 * simulation.params().dt))));
  const model::ClothOnScreen cloth = model::MeasureClothOnScreen(simulation.model(), simulation.state(), camera);
  const sim::SimParams& p = simulation.params();
  return {model::MeasureFrameDefect(simulation.Snapshot(), camera, frame_steps).error_px,
          model::ResolutionErrorPx(cloth, p.width, p.height, p.cols, p.rows)};
}

void Fly(sim::Simulation<float>* simulation, double seconds) {
  for (int i = 0; i < int(std::lround(seconds / simulation->params().dt)); ++i) simulation->Step();
}

}  // namespace

void AutoChoice(const std::string& csv) {
  Table table({"scene", "distance", "image", "auto_chose", "estimated_px", "measured_px", "measured_time_px",
               "estimated_cost", "preset_model_px", "preset_model_cost"},
              csv);
  const int images[][2] = {{1280, 720}, {640, 360}};
  for (const std::string& preset : PresetNames()) {
    const Scene scene = LoadScene(preset);
    sim::SimParams params = scene.sim;
    params.threads = 1;
    sim::Simulation<float> start(params, scene.wind, scene.seed);
    Fly(&start, kFirstSeconds);
    const sim::SimulationSnapshot<float> snapshot = start.Snapshot();
    for (const double distance : {1.0, 3.0, 10.0}) {
      for (const auto& image : images) {
        render::Camera camera = scene.camera;
        camera.eye = camera.target + distance * (camera.eye - camera.target);
        camera.width = image[0];
        camera.height = image[1];
        model::AutoSettings settings;
        settings.collision_passes = start.self_collision_stats().passes;
        const model::ModelDecision decision = model::DecideModel(snapshot, camera, settings);
        sim::Simulation<float> chosen(snapshot), preset_model(snapshot);
        sim::SimParams switched = chosen.params();
        switched.integrator = decision.integrator;
        switched.solver_iterations = decision.solver_iterations;
        chosen.SetParams(switched);
        chosen.Regrid(decision.cols, decision.rows);
        Fly(&chosen, kAfterSeconds);
        Fly(&preset_model, kAfterSeconds);
        const double preset_cost = model::CostModel::Fitted().RealTimeFraction(
            preset_model.params(), preset_model.substeps(), preset_model.self_collision_stats().passes);
        const Measured measured = MeasuredError(chosen, camera);
        table.Add({preset, Table::Number(distance), std::to_string(image[0]) + "x" + std::to_string(image[1]),
                   model::Describe(decision), Table::Number(decision.error_px), Table::Number(measured.total()),
                   Table::Number(measured.time), Table::Number(decision.cost),
                   Table::Number(MeasuredError(preset_model, camera).total()), Table::Number(preset_cost)});
      }
    }
  }
}

}  // namespace flagsim::lab
