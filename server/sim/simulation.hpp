// The flag in time: model, state, wind and integrator, stepped at a fixed dt with a guard.
//
// One step (dt):
//   checkpoint   every kCheckpointInterval steps, and whenever parameters or wind change
//   advance      n substeps of the integrator: n from its stability limit (with a safety
//                factor) or the `substeps` parameter, times the guard's factor; after each, nodes
//                in the pole or the ground are put back on its surface (collision/obstacles.hpp)
//   collide      with self_collision, the motion is corrected so that the cloth does not pass
//                through itself (collision/self_collision.hpp): after the step, or after each of several
//                groups of its substeps where nodes move fast for the grid (CollisionPasses).
//                Both corrections keep what the integrator carries between substeps: a lag of
//                one substep at a contact, as with SetControls, rather than a new
//                factorisation at every touch.
//   guard        a state with non-finite values, a runaway node or a runaway spring rolls back
//                to the checkpoint and redoes the lost steps with twice the substeps; past
//                kMaxGuardFactor an explicit integrator gives way to an unconditionally stable
//                one, and an integrator that is already stable restarts the flag at rest. The
//                flag never leaves a step bad, and what happened is kept as a GuardEvent.
//   sleep        a flag in calm air that moved less than kSleepDistance over kStepsToSleep
//                steps and is slower than kSleepSpeed sleeps: its steps only move the clock. Any new wind,
//                parameters or a restart wake it. Whether it sleeps depends on the state alone, so a replay
//                sleeps and wakes at the same steps.
#pragma once

#include <algorithm>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "server/parallel/worker_pool.hpp"
#include "server/sim/cloth_model.hpp"
#include "server/sim/cloth_state.hpp"
#include "server/sim/collision/self_collision.hpp"
#include "server/sim/forces.hpp"
#include "server/sim/integrator.hpp"
#include "server/sim/node_vectors.hpp"
#include "server/sim/sim_params.hpp"
#include "server/sim/wind_field.hpp"

namespace flagsim::sim {

/// What the guard found and did about it.
struct GuardEvent {
  int64_t step = -1;    ///< the step that went bad; -1: nothing yet
  std::string problem;  ///< e.g. "a node at 1.2e+03 m/s"
  std::string action;   ///< e.g. "redid 16 steps at 4x the substeps"
  std::string Describe() const;
};

/// What a simulation carries from one step to the next besides its state, so that a snapshot
/// holds all the next steps depend on. An empty vector carries nothing.
template <typename Real>
struct CarriedState {
  NodeVectors<Real> integrator;  ///< Integrator::Memory(): forces or a first guess from the last substep
  ClothState<Real> rollback;     ///< the guard's checkpoint when it is an earlier step's; empty: this one
  int calm_steps = 0;            ///< the sleep watch: steps in a row in calm air,
  NodeVectors<Real> calm_start;  ///<   and the positions when the calm began (when calm_steps > 0)
};

/// A simulation at a step boundary (Simulation::Snapshot): all its next steps depend on, so that
/// a simulation built from it continues bit for bit as the original does.
template <typename Real>
struct SimulationSnapshot {
  SimParams params;  ///< as in use, an integrator the guard chose included
  WindFieldState wind;
  ClothState<Real> state;
  int substeps = 1;        ///< per step before the guard's factor (SetSubsteps may have fixed them)
  int guard_factor = 1;    ///< the guard's multiple of the substeps
  int64_t good_steps = 0;  ///< steps since the guard last acted
  int64_t recoveries = 0;
  bool sleeping = false;
  CarriedState<Real> carried;  ///< {} for a fresh start: nothing carried, the guard's checkpoint here
};

/// Substeps per step a flag may ask for or need (the `substeps` parameter, or what SubstepsFor
/// finds at the settings a scene or its keyframes reach): beyond, no server keeps up, and the
/// parameter table and the timeline refuse such settings.
inline constexpr int kMaxSubsteps = 4096;
/// Substeps per step (before the guard's factor) that SubstepsFor returns and SetSubsteps
/// accepts at most. Above kMaxSubsteps on purpose: a flag past that limit gets its need computed
/// as it is, so that the check against kMaxSubsteps reports it rather than a clamped value.
inline constexpr int kMaxComputedSubsteps = 1 << 16;

/// The threads a step of a `nodes`-node flag uses (SimParams::min_nodes_per_thread), no more than
/// the pool allows now (WorkerPool::Threads).
inline int StepThreads(int nodes, const SimParams& params) {
  const int wanted = std::max(1, std::min(params.threads, nodes / std::max(1, params.min_nodes_per_thread)));
  return WorkerPool::Shared().Threads(wanted);
}

/// Self-collision passes come after every this much of the shortest grid spacing that the
/// fastest node travels (Simulation::CollisionPasses). At 0.5 the 256 x 192 breeze took 5.3 passes
/// a step; at 1.0, 3.3, and 3 s of it, 10 s of a gale at 32 x 24, 5 s at 64 x 48 and 2 s at
/// 128 x 96 ran with no guard event and no crossing at any 0.1 s check, for 7 % less CPU at 64 x 48.
inline constexpr double kCollisionReach = 1.0;

/// Substeps per step that `params` asks for: its `substeps` or, when that is 0, enough to stay
/// within the integrator's stability limit on the grid's frequency bound (with kSafety).
int SubstepsFor(const SimParams& params);

/// Substeps per step that keep every control setting between `least` and `most` stable (two
/// settings of one flag that differ only in their ForceCoefficients): each integrator's stable
/// step falls as the top frequency and damping rate grow, and rises with the damping ratio and
/// friction that bound every mode's damping from below; so it is taken at the frequency and
/// damping rate of the most stiffness, damping and friction, and at the ratio of the least
/// damping to the most stiffness and at the least friction. SubstepsFor(p) = SubstepsForRange(p, p).
int SubstepsForRange(const SimParams& least, const SimParams& most);

template <typename Real>
class Simulation {
 public:
  static constexpr double kSafety = 0.8;           ///< fraction of the stability limit used
  static constexpr int kCheckpointInterval = 16;   ///< steps
  static constexpr double kRunawaySpeed = 1000.0;  ///< m/s: any node faster is a blow-up
  static constexpr double kRunawayStretch = 5.0;   ///< a structural spring this many times its rest length
  static constexpr int kMaxGuardFactor = 16;       ///< the most the guard multiplies the substeps by
  /// Where an explicit integrator goes when even kMaxGuardFactor times the substeps fail.
  static constexpr IntegratorKind kStableFallback = IntegratorKind::kXpbd;
  // Float rounding alone keeps the stiffest modes of a resting flag jittering at about 1e-3 m/s
  // (measured, 32 x 24 flag) around a fixed pose, so sleep is judged by how far nodes went.
  static constexpr int kStepsToSleep = 256;       ///< steps of calm air watched
  static constexpr double kSleepDistance = 1e-3;  ///< m: no node moved farther over them
  static constexpr double kSleepSpeed = 1e-2;     ///< m/s: and none is faster at the end

  Simulation(const SimParams& params, const WindSettings& wind, uint64_t seed = 1);
  /// Resumes from a snapshot: the next steps are those the snapshot's simulation takes.
  explicit Simulation(const SimulationSnapshot<Real>& snapshot);

  /// This step boundary as a snapshot, what the integrator, the guard and the sleep watch carry
  /// included. A pure read: a run that takes snapshots steps as one that takes none, and a
  /// simulation resumed from one takes the same steps as this one.
  SimulationSnapshot<Real> Snapshot() const;

  /// Advances one step of params().dt.
  void Step();

  /// Applies new parameters between steps. A new grid (cols, rows, width, height), mass, pole
  /// height or imperfection rebuilds the flag at rest; other changes keep its motion.
  void SetParams(const SimParams& params);
  void SetWind(const WindSettings& wind);

  /// The light path for controls that move at every step (the keyframe timeline), between
  /// steps: the forces' coefficients and `wind`.
  /// Spring constants are updated in place and the wind set from now; no checkpoint is taken,
  /// no frequency estimated, and the integrator keeps what it carries between substeps (forces
  /// from the last, a factorisation), a lag of one step in coefficients that move continuously.
  /// A change wakes the flag. The substeps stay as they are: SetSubsteps chooses them for the
  /// range of settings the controls will pass through.
  void SetControls(const ForceCoefficients& forces, const WindSettings& wind);
  /// Fixes the substeps per step (before the guard's factor) until the next SetParams.
  void SetSubsteps(int substeps);

  /// The flag on a grid of `cols` x `rows` nodes with its motion kept: positions and velocities
  /// resampled over the cloth's (u, v) (resample.hpp); time and step go on. What the automatic
  /// model does between steps; a grid set by SetParams starts at rest instead.
  void Regrid(int cols, int rows);

  /// The flag back at rest, flat, in its initial pose; time and step go on.
  void RestartFlag();
  /// The flag back in `pose` (its positions and velocities; the same grid), time and step going on.
  void RestartFlag(const ClothState<Real>& pose);

  /// The parameters in use: as set, except an integrator the guard replaced.
  const SimParams& params() const { return params_; }
  const ClothModel<Real>& model() const { return model_; }
  const ClothState<Real>& state() const { return state_; }
  const WindField& wind() const { return wind_; }
  int substeps() const { return substeps_ * guard_factor_; }
  int64_t recoveries() const { return recoveries_; }
  const GuardEvent& last_guard_event() const { return last_event_; }
  bool sleeping() const { return sleeping_; }
  /// What self-collision did in the last step, over all its passes (all zero when it is off).
  const SelfCollisionStats& self_collision_stats() const { return collision_stats_; }
  uint64_t Hash() const { return StateHash(state_); }

 private:
  void BuildModel();
  void ChooseIntegrator();
  /// One step of substeps and corrections; returns Problem() of the result.
  std::string Advance(double* fastest = nullptr);
  int CollisionPasses(int substeps) const;
  /// "" if the state is sound, else what is wrong with it; `fastest` gets the top node speed.
  std::string Problem(double* fastest = nullptr) const;
  void WatchForSleep(double fastest);
  void Wake();
  void Recover(const std::string& problem);
  bool Escalate(int64_t lost, GuardEvent* event);
  void Checkpoint() { checkpoint_ = state_; }
  /// Takes up what a snapshot carries (the integrator's memory, the rollback point, the watch).
  void Carry(const CarriedState<Real>& carried);

  SimParams params_;
  ClothModel<Real> model_;
  std::unique_ptr<SelfCollision<Real>> self_collision_;  ///< built with the model
  SelfCollisionStats collision_stats_;
  ClothState<Real> state_;
  ClothState<Real> step_start_;  ///< the state before the step being taken
  ClothState<Real> checkpoint_;
  WindField wind_;
  ForceEvaluator<Real> evaluator_;
  std::unique_ptr<Integrator<Real>> integrator_;
  int substeps_ = 1;      ///< from the stability limit or the parameter
  int guard_factor_ = 1;  ///< doubled by each recovery, halved after a long run of good steps
  int64_t recoveries_ = 0;
  int64_t good_steps_ = 0;  ///< since the last recovery
  GuardEvent last_event_;
  int calm_steps_ = 0;            ///< steps in a row in calm air, up to kStepsToSleep
  NodeVectors<Real> calm_start_;  ///< positions when the calm began
  bool sleeping_ = false;
};

}  // namespace flagsim::sim
