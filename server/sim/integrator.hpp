// Time integrators over one force law. Each advances the state by one substep h; the
// simulation picks h from the integrator's stability limit and the grid's frequency bound.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "server/sim/cloth_model.hpp"
#include "server/sim/cloth_state.hpp"
#include "server/sim/forces.hpp"
#include "server/sim/node_vectors.hpp"
#include "server/sim/sim_params.hpp"
#include "server/sim/wind_field.hpp"

namespace flagsim::sim {

/// What a substep reads besides the state.
template <typename Real>
struct StepContext {
  const ClothModel<Real>& model;
  const SimParams& params;
  const WindField& wind;
  ForceEvaluator<Real>& evaluator;
};

template <typename Real>
class Integrator {
 public:
  virtual ~Integrator() = default;
  /// (x, v, t) => (x, v, t + h). Pinned nodes keep their positions and zero velocity.
  virtual void Substep(const StepContext<Real>& context, double h, ClothState<Real>* state) = 0;
  /// The largest stable h for a grid whose frequencies are bounded by `bound`; +inf if none.
  virtual double StableStep(const FrequencyBound& bound) const = 0;
  /// Forgets whatever is carried from one substep to the next (forces evaluated at the end of
  /// the last substep, factorisations). The simulation calls it whenever the state, parameters
  /// or wind change other than by Substep.
  virtual void Reset() {}
  /// What is carried from one substep to the next that changes the next one's result, for a
  /// snapshot: at most a 3-vector per node; empty if nothing (a factorisation is rebuilt from the
  /// model alone, the same bit for bit).
  virtual NodeVectors<Real> Memory() const { return {}; }
  /// Takes up another integrator's Memory() (of the same kind and grid), so that the next
  /// substep is the one that integrator would take; an empty memory is Reset().
  virtual void Recall(const NodeVectors<Real>& memory) {
    if (memory.x.empty()) Reset();
  }
};

template <typename Real>
std::unique_ptr<Integrator<Real>> MakeIntegrator(IntegratorKind kind);

// Each integrator's own factory, defined in its file; MakeIntegrator picks one.
template <typename Real>
std::unique_ptr<Integrator<Real>> MakeSymplecticEuler(bool seed_friction);
template <typename Real>
std::unique_ptr<Integrator<Real>> MakeExplicitEuler();
template <typename Real>
std::unique_ptr<Integrator<Real>> MakeVelocityVerlet();
template <typename Real>
std::unique_ptr<Integrator<Real>> MakeRk4();
template <typename Real>
std::unique_ptr<Integrator<Real>> MakeXpbd();
template <typename Real>
std::unique_ptr<Integrator<Real>> MakeImplicitEuler();
template <typename Real>
std::unique_ptr<Integrator<Real>> MakeProjectiveDynamics();

/// Names as PARAM and scene files spell them, in IntegratorKind order.
const std::vector<std::string>& IntegratorNames();
std::string IntegratorName(IntegratorKind kind);

}  // namespace flagsim::sim
