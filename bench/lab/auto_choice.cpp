// What `auto` chooses (server/model/auto_model.hpp) against every fixed model it could have run.
//
// Each preset is flown 1 s from rest on its own model; from that snapshot, at six views (its own
// camera, 3 and 10 times farther, at 1280 x 720 and 640 x 360):
//   auto       DecideModel at the view; the flag switched to its choice (Simulation::Regrid and
//              the integrator), flown another second, and its screen_error measured there (the
//              frame defect and the resolution error of the state it reached);
//   fixed      every method auto may use on every grid of its ladder, each switched from the same
//              snapshot and flown the same second once, its screen_error measured at every view;
//              the cheapest whose measured error is within the budget at this view ("cheapest"),
//              and the cheapest within it at the preset's own view at this image size ("own
//              view"): what a user who set the model once for the close-up would pay everywhere.
// With --csv, every fixed model's cost and measured error (time and grid parts) at every view go
// to a second file beside it (auto-models.csv): the work-precision chart of screen_error with
// auto's points (bench/charts/lab_auto.gp).
// Every cost is the cost model's (cost_model.hpp) at the substeps and self-collision passes of
// the flown run's last step, the same arithmetic for auto and for the fixed models, so that the
// comparison does not depend on how busy the machine was.
#include <cmath>
#include <fstream>
#include <limits>
#include <optional>
#include <vector>

#include "bench/lab/experiments.hpp"
#include "bench/lab/table.hpp"
#include "server/model/auto_model.hpp"
#include "server/model/frame_defect.hpp"
#include "server/model/resolution_error.hpp"
#include "server/scene/scene_file.hpp"

namespace flagsim::lab {
namespace {

constexpr double kFirstSeconds = 1.0, kAfterSeconds = 1.0;
constexpr double kBudgetPx = model::AutoSettings{}.budget_px;

/// A model of the flag: method and grid.
struct FixedModel {
  sim::IntegratorKind integrator;
  int iterations;
  int cols, rows;
};

/// "se 32x24", "verlet 64x48", "rk4 24x18", "xpbd2 128x96": short enough for the table's columns.
std::string Name(const FixedModel& m) {
  const std::string method = m.integrator == sim::IntegratorKind::kSymplecticEuler ? "se"
                             : model::TakesIterations(m.integrator)
                                 ? sim::IntegratorName(m.integrator) + std::to_string(m.iterations)
                                 : sim::IntegratorName(m.integrator);
  return method + " " + std::to_string(m.cols) + "x" + std::to_string(m.rows);
}

/// The preset's camera moved back along its line of sight, `distance` times as far, at an image size.
struct View {
  double distance;
  int width, height;
  render::Camera camera;
};

std::vector<View> ViewsOf(const Scene& scene) {
  std::vector<View> views;
  for (const double distance : {1.0, 3.0, 10.0}) {
    for (const auto& [width, height] : {std::pair{1280, 720}, std::pair{640, 360}}) {
      render::Camera camera = scene.camera;
      camera.eye = camera.target + distance * (camera.eye - camera.target);
      camera.width = width;
      camera.height = height;
      views.push_back({distance, width, height, camera});
    }
  }
  return views;
}

/// screen_error as measured, px: the time step's part (the frame defect) and the grid's.
struct MeasuredError {
  double time_px = 0, resolution_px = 0;
  double total() const { return time_px + resolution_px; }
};

/// screen_error of a simulation's present state at `camera`.
MeasuredError Measure(const sim::Simulation<float>& simulation, const render::Camera& camera) {
  const int frame_steps = std::max(1, int(std::lround(1.0 / (30.0 * simulation.params().dt))));
  const model::ClothOnScreen cloth = model::MeasureClothOnScreen(simulation.model(), simulation.state(), camera);
  const sim::SimParams& p = simulation.params();
  return {model::MeasureFrameDefect(simulation.Snapshot(), camera, frame_steps).error_px,
          model::ResolutionErrorPx(cloth, p.width, p.height, p.cols, p.rows)};
}

/// A fixed model flown from `snapshot`: its cost and its measured error at every view.
struct Flown {
  FixedModel model;
  double cost = 0;                    ///< CPU s per simulated s, by the cost model
  std::vector<MeasuredError> errors;  ///< at each view
  double error_px(std::size_t view) const { return errors[view].total(); }
};

bool Same(const FixedModel& a, const FixedModel& b) {
  return a.integrator == b.integrator && a.cols == b.cols && a.rows == b.rows &&
         (!model::TakesIterations(a.integrator) || a.iterations == b.iterations);
}

Flown Fly(const sim::SimulationSnapshot<float>& snapshot, const FixedModel& m, const std::vector<View>& views) {
  sim::Simulation<float> simulation(snapshot);
  sim::SimParams params = simulation.params();
  params.integrator = m.integrator;
  params.solver_iterations = m.iterations;
  params.substeps = 0;
  simulation.SetParams(params);
  simulation.Regrid(m.cols, m.rows);
  for (int i = 0; i < int(std::lround(kAfterSeconds / params.dt)); ++i) simulation.Step();
  Flown flown{m, model::CostModel::Fitted().RealTimeFraction(simulation.params(), simulation.substeps(),
                                                             simulation.self_collision_stats().passes),
              {}};
  for (const View& view : views) flown.errors.push_back(Measure(simulation, view.camera));
  return flown;
}

/// The cheapest of `flown` within the budget at view `v`; none if no model meets it.
const Flown* Cheapest(const std::vector<Flown>& flown, std::size_t v) {
  const Flown* best = nullptr;
  for (const Flown& f : flown) {
    if (f.error_px(v) <= kBudgetPx && (!best || f.cost < best->cost)) best = &f;
  }
  return best;
}

std::string NameOrNone(const Flown* f) { return f ? Name(f->model) : "none"; }
std::string Cost(const Flown* f) { return f ? Table::Number(f->cost) : "-"; }

std::string ImageName(const View& view) { return std::to_string(view.width) + "x" + std::to_string(view.height); }

/// The work-precision points of one preset: every fixed model at every view, its cost and its
/// measured error in its two parts, and whether auto chose it there. One CSV row each.
void WriteModels(const std::string& preset, const std::vector<View>& views, const std::vector<Flown>& fixed,
                 const std::vector<FixedModel>& chosen, std::ofstream* out) {
  for (std::size_t v = 0; v < views.size(); ++v) {
    for (const Flown& f : fixed) {
      const MeasuredError& e = f.errors[v];
      *out << preset << ',' << views[v].distance << ',' << ImageName(views[v]) << ',' << Name(f.model) << ','
           << sim::IntegratorName(f.model.integrator) << ',' << f.model.cols << ',' << f.cost << ',' << e.time_px
           << ',' << e.resolution_px << ',' << e.total() << ',' << (Same(f.model, chosen[v]) ? 1 : 0) << '\n';
    }
  }
}

}  // namespace

// The table of auto's choices, and beside `csv` (auto.csv) every fixed model's point
// (auto-models.csv) for bench/charts/lab_auto.gp.
void AutoChoice(const std::string& csv) {
  Table table({"scene", "distance", "image", "auto_chose", "estimated_px", "measured_px", "auto_cost", "cheapest",
               "cheapest_px", "cheapest_cost", "own_view_model", "own_view_px", "own_view_cost"},
              csv);
  std::ofstream models;
  if (!csv.empty()) {
    models.open(csv.substr(0, csv.rfind(".csv")) + "-models.csv");
    models << "scene,distance,image,model,method,cols,cost,time_px,resolution_px,measured_px,auto\n";
  }
  for (const std::string& preset : PresetNames()) {
    const Scene scene = LoadScene(preset);
    sim::SimParams params = scene.sim;
    params.threads = 1;
    sim::Simulation<float> start(params, scene.wind, scene.seed);
    for (int i = 0; i < int(std::lround(kFirstSeconds / params.dt)); ++i) start.Step();
    const sim::SimulationSnapshot<float> snapshot = start.Snapshot();
    const std::vector<View> views = ViewsOf(scene);
    std::vector<Flown> fixed;
    for (const int cols : model::kGridLadder) {
      const int rows = int(std::lround(cols * double(params.rows) / params.cols));
      for (const model::AutoMethod& method : model::kAutoMethods) {
        fixed.push_back(Fly(snapshot, {method.integrator, method.iterations, cols, rows}, views));
      }
    }
    std::vector<FixedModel> chosen_models;
    for (std::size_t v = 0; v < views.size(); ++v) {
      const View& view = views[v];
      model::AutoSettings settings;
      settings.collision_passes = start.self_collision_stats().passes;
      settings.rows_per_col = double(params.rows) / params.cols;
      const model::ModelDecision decision = model::DecideModel(snapshot, view.camera, settings);
      const Flown chosen = Fly(snapshot, {decision.integrator, decision.solver_iterations, decision.cols, decision.rows},
                               {view});
      chosen_models.push_back(chosen.model);
      const Flown* cheapest = Cheapest(fixed, v);
      const Flown* own_view = Cheapest(fixed, v % 2);  // the preset's own distance, this image size
      table.Add({preset, Table::Number(view.distance), ImageName(view), Name(chosen.model),
                 Table::Number(decision.error_px), Table::Number(chosen.error_px(0)), Table::Number(chosen.cost),
                 NameOrNone(cheapest), cheapest ? Table::Number(cheapest->error_px(v)) : "-", Cost(cheapest),
                 NameOrNone(own_view), own_view ? Table::Number(own_view->error_px(v)) : "-", Cost(own_view)});
    }
    if (models.is_open()) WriteModels(preset, views, fixed, chosen_models, &models);
  }
}

}  // namespace flagsim::lab
