#include "server/service/model_governor.hpp"

#include <algorithm>
#include <cmath>

namespace flagsim {

ModelGovernor::~ModelGovernor() {
  if (pending_.valid()) pending_.wait();
}

// Everything from the session's scenes, nothing from how the last steps ran, so that the same
// snapshot gets the same decision in a resumed session too.
model::AutoSettings ModelGovernor::SettingsOf(const Session& session) {
  const Scene& scene = session.scene();
  model::AutoSettings settings;
  settings.integrator = scene.model.auto_integrator;
  settings.grid = scene.model.auto_grid;
  settings.budget_px = scene.model.error_budget;
  settings.cost_budget = scene.model.cost_budget;
  settings.collision_passes = scene.sim.self_collision ? 1 : 0;
  const sim::SimParams& initial = session.initial_scene().sim;
  settings.rows_per_col = double(initial.rows) / initial.cols;
  return settings;
}

namespace {

/// Whether `decision` changes what auto may change in `scene` now (the user may have fixed the
/// integrator or the grid since the question, or the model may be that one already).
bool Switches(const model::ModelDecision& decision, const Scene& scene) {
  const sim::SimParams& now = scene.sim;
  const bool method = decision.integrator != now.integrator ||
                      (model::TakesIterations(decision.integrator) && decision.solver_iterations != now.solver_iterations);
  const bool grid = decision.cols != now.cols || decision.rows != now.rows;
  return (scene.model.auto_integrator && method) || (scene.model.auto_grid && grid);
}

}  // namespace

int64_t ModelGovernor::Steps(double seconds, const Session& session) {
  return std::max<int64_t>(1, std::llround(std::ceil(seconds / session.scene().sim.dt)));
}

std::optional<model::ModelDecision> ModelGovernor::AtBoundary(const Session& session) {
  const int64_t step = session.simulation().state().step;
  std::optional<model::ModelDecision> switch_to;
  if (due_step_ >= 0 && step >= due_step_) {
    last_ = pending_.get();  // waits if the thread is still deciding
    due_step_ = -1;
    if (Switches(last_->chosen, session.scene())) switch_to = last_->chosen;
  }
  const bool changed = session.revision() != asked_revision_ && step >= earliest_question_;
  const bool periodic = step % Steps(kPeriod, session) == 0;
  if (due_step_ < 0 && !session.simulation().sleeping() && (changed || periodic)) Ask(session);
  return switch_to;
}

// snapshot => the governor's thread => DecideModels
void ModelGovernor::Ask(const Session& session) {
  const int64_t step = session.simulation().state().step;
  asked_revision_ = session.revision();
  earliest_question_ = step + Steps(kLeast, session);
  due_step_ = step + Steps(kLatency, session);
  const model::AutoSettings settings = SettingsOf(session);
  pending_ = std::async(std::launch::async,
                        [snapshot = session.simulation().Snapshot(), camera = session.scene().camera, settings] {
                          return model::DecideModels(snapshot, camera, settings);
                        });
}

}  // namespace flagsim
