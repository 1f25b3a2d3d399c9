// The flag in time: model, state, wind and integrator, stepped at a fixed dt with a guard.
//
// One step (dt):
//   checkpoint   every kCheckpointInterval steps, and whenever parameters change
//   advance      n substeps of the integrator, n from its stability limit (with a safety
//                factor) times the guard's factor
//   guard        a non-finite or runaway state rolls back to the checkpoint and redoes the
//                lost steps with twice the substeps; the flag never leaves a step bad
#pragma once

#include <cstdint>
#include <memory>

#include "cloth_model.hpp"
#include "cloth_state.hpp"
#include "forces.hpp"
#include "integrator.hpp"
#include "sim_params.hpp"
#include "wind_field.hpp"

namespace flagsim::sim {

template <typename Real>
class Simulation {
 public:
  static constexpr double kSafety = 0.8;           ///< fraction of the stability limit used
  static constexpr int kCheckpointInterval = 16;   ///< steps
  static constexpr double kRunawaySpeed = 1000.0;  ///< m/s: any node faster is a blow-up
  static constexpr int kMaxGuardFactor = 1024;

  Simulation(const SimParams& params, const WindSettings& wind, uint64_t seed = 1);

  /// Advances one step of params().dt.
  void Step();

  /// Applies new parameters between steps. A new grid (cols, rows, width, height) or mass
  /// rebuilds the flag at rest; other changes keep its motion.
  void SetParams(const SimParams& params);
  void SetWind(const WindSettings& wind);
  /// The flag back at rest, flat, in its initial pose; time and step go on.
  void RestartFlag();

  const SimParams& params() const { return params_; }
  const ClothModel<Real>& model() const { return model_; }
  const ClothState<Real>& state() const { return state_; }
  const WindField& wind() const { return wind_; }
  int substeps() const { return substeps_ * guard_factor_; }
  int64_t recoveries() const { return recoveries_; }
  uint64_t Hash() const { return StateHash(state_); }

 private:
  void Rebuild();
  void Advance();
  bool StateIsSound() const;
  void Recover();
  void Checkpoint() { checkpoint_ = state_; }

  SimParams params_;
  ClothModel<Real> model_;
  ClothState<Real> state_;
  ClothState<Real> checkpoint_;
  WindField wind_;
  ForceEvaluator<Real> evaluator_;
  std::unique_ptr<Integrator<Real>> integrator_;
  int substeps_ = 1;      ///< from the stability limit
  int guard_factor_ = 1;  ///< doubled by each recovery, halved after a long run of good steps
  int64_t recoveries_ = 0;
  int64_t good_steps_ = 0;  ///< since the last recovery
};

}  // namespace flagsim::sim
