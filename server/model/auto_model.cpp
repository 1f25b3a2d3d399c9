#include "server/model/auto_model.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "server/model/frame_defect.hpp"
#include "server/model/resolution_error.hpp"

namespace flagsim::model {
namespace {

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
  AutoMethod method;
  int substeps = 1;
  double time_px = 0;
};

Probe ProbeMethod(const sim::SimulationSnapshot<float>& snapshot, const render::Camera& camera, AutoMethod method,
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

/// Rows of the ladder's grid of `cols` columns.
int RowsFor(double rows_per_col, int cols) { return std::max(2, int(std::lround(cols * rows_per_col))); }

/// The snapshot the probes start from: the snapshot itself, or on a grid finer than kProbeCols
/// the same flag resampled to kProbeCols (a probe costs what its grid costs, and the time error
/// scales to the other grids by their substeps), stepped on one thread beside the server's.
sim::SimulationSnapshot<float> ProbeStart(const sim::SimulationSnapshot<float>& snapshot, double rows_per_col) {
  sim::SimulationSnapshot<float> start = snapshot;
  start.params.threads = 1;
  if (snapshot.params.cols <= kProbeCols) return start;
  sim::Simulation<float> coarse(start);
  coarse.Regrid(kProbeCols, RowsFor(rows_per_col, kProbeCols));
  return coarse.Snapshot();
}

bool SameMethod(const AutoMethod& a, const AutoMethod& b) {
  return a.integrator == b.integrator && (!TakesIterations(a.integrator) || a.iterations == b.iterations);
}

/// What auto estimates of `probe`'s method on a grid of cols x rows (spacing `ratio` times the
/// grid in force's); none when it would need more substeps than any server keeps up with.
/// Substeps of the explicit methods on one grid: symplectic Euler's from that grid's stability
/// limit (sim::SubstepsFor, which estimates the grid's highest frequency: the costly part), each
/// other method's in the ratio of their stable steps, as the probes found it on the probe grid.
struct ExplicitSubsteps {
  int symplectic_euler = 1;        ///< on this grid
  int probe_symplectic_euler = 1;  ///< on the probe grid
  int For(const Probe& probe) const {
    return std::max(1, int(std::ceil(double(symplectic_euler) * probe.substeps / probe_symplectic_euler)));
  }
};

std::optional<ModelDecision> Estimate(const Probe& probe, const sim::SimParams& now, int cols, int rows, double ratio,
                                      const ExplicitSubsteps& explicit_substeps, const ClothOnScreen& cloth,
                                      const AutoSettings& settings, const CostModel& costs) {
  ModelDecision d;
  d.integrator = probe.method.integrator;
  d.solver_iterations = probe.method.iterations;
  d.cols = cols;
  d.rows = rows;
  sim::SimParams params = now;
  params.integrator = d.integrator;
  params.solver_iterations = d.solver_iterations;
  params.cols = cols;
  params.rows = rows;
  params.substeps = 0;
  // An explicit method's substep follows this grid's stability limit, and its defect the
  // substep: e ~ h^p. The others take the probe's substeps on any grid, and its defect.
  const bool explicit_method = Explicit(d.integrator);
  d.substeps = explicit_method ? explicit_substeps.For(probe) : probe.substeps;
  if (d.substeps > sim::kMaxSubsteps) return std::nullopt;  // the parameter table's limit
  d.time_px = explicit_method ? probe.time_px * std::pow(double(probe.substeps) / d.substeps, OrderOf(d.integrator))
                              : probe.time_px;
  d.resolution_px = ResolutionErrorPx(cloth, now.width, now.height, cols, rows);
  d.error_px = d.time_px + d.resolution_px;
  d.cost = costs.RealTimeFraction(params, d.substeps, settings.collision_passes / ratio);
  return d;
}

}  // namespace

ModelDecisions DecideModels(const sim::SimulationSnapshot<float>& snapshot, const render::Camera& camera,
                            const AutoSettings& settings, const CostModel& costs) {
  const sim::SimParams& now = snapshot.params;
  const int frame_steps = std::max(1, int(std::lround(1.0 / (30.0 * now.dt))));  // a frame at 30 Hz
  const sim::ClothModel<float> model = sim::BuildClothModel<float>(now);
  const ClothOnScreen cloth = MeasureClothOnScreen(model, snapshot.state, camera);
  // Every method auto may use, and the one in force, each probed once.
  const sim::SimulationSnapshot<float> start = ProbeStart(snapshot, settings.rows_per_col);
  const AutoMethod in_force{now.integrator, now.solver_iterations};
  std::vector<Probe> probes;
  bool in_force_probed = false;
  for (const AutoMethod& method : kAutoMethods) {
    probes.push_back(ProbeMethod(start, camera, method, frame_steps));
    in_force_probed |= SameMethod(method, in_force);
  }
  if (!in_force_probed) probes.push_back(ProbeMethod(start, camera, in_force, frame_steps));
  // Every grid of the ladder, and the one in force.
  std::vector<std::pair<int, int>> grids;
  for (const int cols : kGridLadder) grids.emplace_back(cols, RowsFor(settings.rows_per_col, cols));
  if (std::find(grids.begin(), grids.end(), std::pair{now.cols, now.rows}) == grids.end()) {
    grids.emplace_back(now.cols, now.rows);
  }
  // Candidates: every probe on every grid; those auto may switch to under `settings`.
  const double spacing_now = Spacing(now, now.cols, now.rows);
  std::vector<ModelDecision> decisions;
  std::vector<Candidate> all, allowed;
  std::vector<int> allowed_index;  // into decisions
  int current = -1, current_allowed = -1;
  for (const auto& [cols, rows] : grids) {
    const double ratio = Spacing(now, cols, rows) / spacing_now;  // > 1: coarser
    sim::SimParams symplectic = now;
    symplectic.integrator = sim::IntegratorKind::kSymplecticEuler;
    symplectic.cols = cols;
    symplectic.rows = rows;
    symplectic.substeps = 0;
    const ExplicitSubsteps explicit_substeps{sim::SubstepsFor(symplectic), probes.front().substeps};
    for (const Probe& probe : probes) {
      const std::optional<ModelDecision> d =
          Estimate(probe, now, cols, rows, ratio, explicit_substeps, cloth, settings, costs);
      if (!d) continue;
      const Candidate candidate{d->integrator, d->substeps, cols, rows, d->error_px, d->cost};
      const bool same_method = SameMethod(probe.method, in_force);
      const bool same_grid = cols == now.cols && rows == now.rows;
      if (same_method && same_grid) current = int(decisions.size());
      if ((settings.integrator || same_method) && (settings.grid || same_grid)) {
        if (same_method && same_grid) current_allowed = int(allowed.size());
        allowed.push_back(candidate);
        allowed_index.push_back(int(decisions.size()));
      }
      all.push_back(candidate);
      decisions.push_back(*d);
    }
  }
  ModelDecisions result;
  const auto pick = [&](const std::vector<Candidate>& among, int keep, const std::vector<int>* index) {
    const Choice choice = ChooseModel(among, settings.budget_px, settings.cost_budget, keep, settings.hysteresis);
    ModelDecision decision = decisions[index ? (*index)[choice.index] : choice.index];
    decision.kind = choice.kind;
    return decision;
  };
  result.free = pick(all, current, nullptr);
  result.chosen = allowed.empty() ? result.free : pick(allowed, current_allowed, &allowed_index);
  if (current >= 0) result.in_force = decisions[current];
  result.in_force_estimated = current >= 0;
  return result;
}

ModelDecision DecideModel(const sim::SimulationSnapshot<float>& snapshot, const render::Camera& camera,
                          const AutoSettings& settings, const CostModel& costs) {
  return DecideModels(snapshot, camera, settings, costs).chosen;
}

std::string Describe(const ModelDecision& d) {
  char text[200];
  const std::string iterations = TakesIterations(d.integrator) ? " (" + std::to_string(d.solver_iterations) + " iterations)" : "";
  std::snprintf(text, sizeof(text), "%s%s at %d x %d, %d substep%s: %.2g px, %.2g of real time",
                sim::IntegratorName(d.integrator).c_str(), iterations.c_str(), d.cols, d.rows, d.substeps,
                d.substeps == 1 ? "" : "s", d.error_px, d.cost);
  return text;
}

}  // namespace flagsim::model
