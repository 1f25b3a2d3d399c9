#include "server/model/auto_model.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "server/model/frame_defect.hpp"
#include "server/model/resolution_error.hpp"

namespace flagsim::model {
namespace {

/// An integrator auto may use, with its iterations where it takes them.
struct Method {
  sim::IntegratorKind integrator;
  int iterations;
};
constexpr Method kMethods[] = {{sim::IntegratorKind::kSymplecticEuler, 10}, {sim::IntegratorKind::kVelocityVerlet, 10},
                               {sim::IntegratorKind::kRk4, 10},             {sim::IntegratorKind::kXpbd, 2},
                               {sim::IntegratorKind::kXpbd, 10},            {sim::IntegratorKind::kImplicitEuler, 10},
                               {sim::IntegratorKind::kProjectiveDynamics, 10}};

bool Explicit(sim::IntegratorKind kind) {
  return kind == sim::IntegratorKind::kSymplecticEuler || kind == sim::IntegratorKind::kVelocityVerlet ||
         kind == sim::IntegratorKind::kRk4 || kind == sim::IntegratorKind::kExplicitEuler ||
         kind == sim::IntegratorKind::kSeed;
}

/// m: the larger grid spacing of cols x rows on the flag.
double Spacing(const sim::SimParams& params, int cols, int rows) {
  return std::max(params.width / (cols - 1), params.height / (rows - 1));
}

/// What one method does on the grid in force: its substeps and its measured frame defect.
struct Probe {
  Method method;
  int substeps = 1;
  double time_px = 0;
};

Probe ProbeMethod(const sim::SimulationSnapshot<float>& snapshot, const render::Camera& camera, Method method,
                  int frame_steps) {
  sim::SimulationSnapshot<float> trial = snapshot;
  trial.params.integrator = method.integrator;
  trial.params.solver_iterations = method.iterations;
  trial.params.substeps = 0;
  trial.substeps = sim::SubstepsFor(trial.params);
  trial.guard_factor = 1;
  trial.carried.integrator = {};  // another integrator's memory means nothing to this one
  Probe probe{method, trial.substeps, 0};
  probe.time_px = MeasureFrameDefect(trial, camera, frame_steps).error_px;
  return probe;
}

bool SameModel(const ModelDecision& a, const sim::SimParams& params) {
  const bool iterates = a.integrator == sim::IntegratorKind::kXpbd ||
                        a.integrator == sim::IntegratorKind::kProjectiveDynamics;
  return a.integrator == params.integrator && a.cols == params.cols && a.rows == params.rows &&
         (!iterates || a.solver_iterations == params.solver_iterations);
}

}  // namespace

ModelDecision DecideModel(const sim::SimulationSnapshot<float>& snapshot, const render::Camera& camera,
                          const AutoSettings& settings, const CostModel& costs) {
  const sim::SimParams& now = snapshot.params;
  const int frame_steps = std::max(1, int(std::lround(1.0 / (30.0 * now.dt))));  // a frame at 30 Hz
  const sim::ClothModel<float> model = sim::BuildClothModel<float>(now);
  const ClothOnScreen cloth = MeasureClothOnScreen(model, snapshot.state, camera);
  // The methods and grids to weigh.
  std::vector<Probe> probes;
  for (const Method& method : kMethods) {
    const bool in_force = method.integrator == now.integrator &&
                          (Explicit(method.integrator) || method.iterations == now.solver_iterations ||
                           method.integrator == sim::IntegratorKind::kImplicitEuler);
    if (settings.integrator || in_force) probes.push_back(ProbeMethod(snapshot, camera, method, frame_steps));
  }
  if (probes.empty()) probes.push_back(ProbeMethod(snapshot, camera, {now.integrator, now.solver_iterations}, frame_steps));
  std::vector<std::pair<int, int>> grids;
  if (settings.grid) {
    for (const int cols : kGridLadder) {
      grids.emplace_back(cols, std::max(2, int(std::lround(double(cols) * (now.rows - 1) / (now.cols - 1)))) );
    }
  } else {
    grids.emplace_back(now.cols, now.rows);
  }
  // Candidates: every probe on every grid.
  const double spacing_now = Spacing(now, now.cols, now.rows);
  std::vector<Candidate> candidates;
  std::vector<ModelDecision> decisions;
  int current = -1;
  for (const auto& [cols, rows] : grids) {
    const double ratio = Spacing(now, cols, rows) / spacing_now;  // > 1: coarser
    for (const Probe& probe : probes) {
      ModelDecision d;
      d.integrator = probe.method.integrator;
      d.solver_iterations = probe.method.iterations;
      d.cols = cols;
      d.rows = rows;
      const bool explicit_method = Explicit(d.integrator);
      d.substeps = explicit_method ? std::max(1, int(std::ceil(probe.substeps / ratio))) : probe.substeps;
      d.time_px = explicit_method ? probe.time_px * std::pow(ratio, OrderOf(d.integrator)) : probe.time_px;
      d.resolution_px = ResolutionErrorPx(cloth, now.width, now.height, cols, rows);
      d.error_px = d.time_px + d.resolution_px;
      sim::SimParams params = now;
      params.integrator = d.integrator;
      params.solver_iterations = d.solver_iterations;
      params.cols = cols;
      params.rows = rows;
      d.cost = costs.RealTimeFraction(params, d.substeps, settings.collision_passes / ratio);
      d.changes = !SameModel(d, now);
      if (!d.changes) current = static_cast<int>(decisions.size());
      candidates.push_back({d.integrator, d.substeps, cols, rows, d.error_px, d.cost});
      decisions.push_back(d);
    }
  }
  const Choice choice = ChooseModel(candidates, settings.budget_px, settings.cost_budget, current, settings.hysteresis);
  ModelDecision decision = decisions[choice.index];
  decision.kind = choice.kind;
  return decision;
}

std::string Describe(const ModelDecision& d) {
  char text[200];
  const bool iterates = d.integrator == sim::IntegratorKind::kXpbd ||
                        d.integrator == sim::IntegratorKind::kProjectiveDynamics;
  const std::string iterations = iterates ? " (" + std::to_string(d.solver_iterations) + " iterations)" : "";
  std::snprintf(text, sizeof(text), "%s%s at %d x %d, %d substep%s: %.2g px, %.2g of real time",
                sim::IntegratorName(d.integrator).c_str(), iterations.c_str(), d.cols, d.rows, d.substeps,
                d.substeps == 1 ? "" : "s", d.error_px, d.cost);
  return text;
}

}  // namespace flagsim::model
