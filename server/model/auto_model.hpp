// `auto`: the model of the flag the server would choose for the picture it draws.
//
// From one snapshot of the simulation, the camera in force (its image size included) and what
// the user left to it (the integrator, the grid or both), it builds candidate models and chooses
// among them by model_choice.hpp:
//   candidates  each grid of the ladder (kGridLadder, at AutoSettings::rows_per_col) and the
//               grid in force, times each integrator auto may use (symplectic Euler, Verlet,
//               RK4, XPBD at 2 and 10 iterations) and the one in force; those auto may switch to
//               keep the grid or the integrator where the user fixed it;
//   time error  frame_defect.hpp, measured for each integrator from this snapshot (a probe: three
//               frame intervals of simulation each), on the grid in force or, where that is finer
//               than kProbeCols columns, on the flag resampled to kProbeCols; on another grid it
//               scales as (h / h_probe)^p for the explicit methods, whose substep h follows that
//               grid's stability limit (sim::SubstepsFor), and stays as measured for the
//               unconditionally stable ones, which take the same substeps on any grid;
//   resolution  resolution_error.hpp from this state's curvature and scale on screen;
//   cost        cost_model.hpp at each candidate's substeps and self-collision
//               passes (those of the last step, scaled by s_now / s: a pass comes every spacing
//               the fastest node travels);
// and the choice is the cheapest within the budget that fits the cost budget, or the most
// accurate that fits, or the cheapest, with hysteresis for the model in force. Everything is
// computed from the snapshot, so the same snapshot gives the same decision; the server journals
// each decision (it depends on the cost budget, the cores this machine gives) so that a replay
// applies the decisions it made rather than deciding again.
#pragma once

#include <string>
#include <vector>

#include "server/model/cost_model.hpp"
#include "server/model/model_choice.hpp"
#include "server/render/camera.hpp"
#include "server/sim/simulation.hpp"

namespace flagsim::model {

/// An integrator auto may use, with its iterations where it takes them.
struct AutoMethod {
  sim::IntegratorKind integrator;
  int iterations;
};
// Implicit Euler and projective dynamics are left out: by the cost model they take 4.85 and
// 3.2 us a node-step (docs/lab/cost-model.txt), 0.47 and 0.30 of a core at 16 x 12 and beyond
// real time from 48 x 36, and no view of the presets had them chosen (docs/lab/auto.csv); their
// probes were two thirds of a decision's time.
inline constexpr AutoMethod kAutoMethods[] = {
    {sim::IntegratorKind::kSymplecticEuler, 10},  // first: ExplicitSubsteps' reference
    {sim::IntegratorKind::kVelocityVerlet, 10},
    {sim::IntegratorKind::kRk4, 10},
    {sim::IntegratorKind::kXpbd, 2},
    {sim::IntegratorKind::kXpbd, 10}};

/// Columns of the grids auto may choose; rows follow AutoSettings::rows_per_col.
inline constexpr int kGridLadder[] = {16, 24, 32, 48, 64, 96, 128};
/// Columns of the grid the integrators are probed on, at most: a finer flag is resampled to it.
inline constexpr int kProbeCols = 24;

struct AutoSettings {
  bool integrator = true;       ///< auto chooses the integrator (else the snapshot's stays)
  bool grid = true;             ///< auto chooses the grid (else the snapshot's stays)
  double budget_px = 1.0;       ///< screen_error allowed
  double cost_budget = 0.8;     ///< CPU seconds per simulated second the flag may take
  double hysteresis = 0.1;      ///< the model in force is kept within this of the best
  double collision_passes = 1;  ///< self-collision passes per step on the grid in force (0 without)
  double rows_per_col = 0.75;   ///< the ladder's grids: rows = round(cols * rows_per_col)
};

/// A model the server can switch to, and what auto estimates of it.
struct ModelDecision {
  sim::IntegratorKind integrator = sim::IntegratorKind::kSymplecticEuler;
  int solver_iterations = 10;
  int cols = 32, rows = 24;
  int substeps = 1;          ///< per step, as estimated (the simulation chooses its own for stability)
  double error_px = 0;       ///< estimated screen_error: time plus resolution
  double time_px = 0, resolution_px = 0;
  double cost = 0;           ///< CPU seconds per simulated second, by the cost model
  ChoiceKind kind = ChoiceKind::kWithinBudget;
};

/// Whether an integrator takes solver_iterations (xpbd, projective dynamics).
inline bool TakesIterations(sim::IntegratorKind kind) {
  return kind == sim::IntegratorKind::kXpbd || kind == sim::IntegratorKind::kProjectiveDynamics;
}

/// What auto decides from one snapshot.
struct ModelDecisions {
  ModelDecision chosen;    ///< among the models `settings` lets auto switch to
  ModelDecision free;      ///< were auto free to choose the integrator and the grid
  ModelDecision in_force;  ///< the model in force, as auto estimates it
  bool in_force_estimated = false;  ///< false: beyond any server (more than sim::kMaxSubsteps)
};

/// What auto would run from `snapshot` seen by `camera`: the candidates are every method auto
/// may use and the one in force, on every grid of the ladder and the one in force.
ModelDecisions DecideModels(const sim::SimulationSnapshot<float>& snapshot, const render::Camera& camera,
                            const AutoSettings& settings, const CostModel& costs = CostModel::Fitted());

/// DecideModels(...).chosen.
ModelDecision DecideModel(const sim::SimulationSnapshot<float>& snapshot, const render::Camera& camera,
                          const AutoSettings& settings, const CostModel& costs = CostModel::Fitted());

/// "xpbd (2 iterations) at 64 x 48, 1 substep: 0.8 px, 0.4 of real time".
std::string Describe(const ModelDecision& decision);

}  // namespace flagsim::model
