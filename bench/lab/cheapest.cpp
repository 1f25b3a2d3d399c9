// The cheapest way to show each preset scene right. For each preset (its own flag and wind,
// 0.5 s from rest) and each integrator, the coarsest of ten steps halving from its stability
// limit or 1/60 s whose worst node stays under one pixel from converged RK4 on the default
// camera's 1280 x 720 image; its cost (CPU seconds per simulated second, float, one thread);
// then the cheapest integrator per scene. The seed's scheme is left out (another ODE).
#include <cmath>

#include "bench/lab/experiments.hpp"
#include "bench/lab/lab_setup.hpp"
#include "bench/lab/table.hpp"
#include "lab/screen_error.hpp"
#include "server/scene/scene_file.hpp"

namespace flagsim::lab {
namespace {

constexpr double kPixel = 1.0;
constexpr int kSteps = 10;

}  // namespace

void Cheapest(const std::string& csv) {
  Table table({"scene", "integrator", "h_s", "largest_px", "cost_s_per_s", "cheapest"}, csv);
  for (const std::string& preset : PresetNames()) {
    const Trial base = PresetTrial(preset, 0.5);
    const render::Camera camera = LoadScene(preset).camera;
    References references(base);
    const sim::ClothState<double>& reference = references.At(references.Converge(1e-6).substeps);
    struct Choice {
      std::string integrator;
      double h = 0, largest = INFINITY, cost = INFINITY;
    };
    std::vector<Choice> choices;
    for (const sim::IntegratorKind kind : AllIntegrators()) {
      if (kind == sim::IntegratorKind::kSeed) continue;
      Trial trial = base;
      trial.params.integrator = kind;
      Choice choice{sim::IntegratorName(kind)};
      for (const double h : StepSweep(trial, kSteps)) {
        const int substeps = SubstepsFor(trial, h);
        const sim::ClothState<double> state = RunFixed<double>(trial, substeps);
        if (!StateIsSound(state)) continue;
        const double largest = ScreenDistance(camera, state, reference).largest;
        if (largest >= kPixel) continue;
        choice = Choice{choice.integrator, trial.horizon / substeps, largest,
                        CostPerSimulatedSecond(trial, substeps, 3)};
        break;
      }
      choices.push_back(choice);
    }
    const auto best = std::min_element(choices.begin(), choices.end(),
                                       [](const Choice& a, const Choice& b) { return a.cost < b.cost; });
    for (const Choice& choice : choices) {
      table.Add({preset, choice.integrator, Table::Number(choice.h), Table::Number(choice.largest),
                 Table::Number(choice.cost), &choice == &*best ? "yes" : ""});
    }
  }
}

}  // namespace flagsim::lab
