// Velocity Verlet (kick, drift, kick), second order with one force evaluation per substep:
//   v' = v + h/2 a_n;  x <- x + h v';  a_{n+1} = a(x, v + h a_n, t + h);  v <- v' + h/2 a_{n+1}
// The forces depend on velocity (spring damping, friction, relative wind), and the velocity
// at the end of the substep is not known when they are evaluated, so they are taken at the
// predictor v + h a_n, which is within O(h^2) of it: the second kick's error is O(h^3) and the
// method stays second order. a_{n+1} is kept for the next substep's first kick (first same as
// last), so Reset() drops it whenever the state changes from outside.
// Stability on x'' = -w^2 x - g x' (found by iterating the update matrix; 2 / w undamped):
//   h < 2 / (g + sqrt(g^2 + w^2)),
// smaller than symplectic Euler's limit once damping is strong, and falling in both w and g,
// so the upper bounds of FrequencyBound give a safe step.
#include <cmath>
#include <limits>

#include "server/sim/integrator.hpp"
#include "server/sim/node_update.hpp"
#include "server/sim/node_vectors.hpp"

namespace flagsim::sim {
namespace {

template <typename Real>
class VelocityVerlet : public Integrator<Real> {
 public:
  void Substep(const StepContext<Real>& context, double h, ClothState<Real>* state) override {
    const ClothModel<Real>& model = context.model;
    const int threads = context.params.threads;
    if (!have_forces_) Evaluate(context, *state, state->time);
    const Real step = Real(h), half = Real(h / 2);
    // Kick and drift; the state's velocity becomes the predictor v + h a_n for the evaluation,
    // and v' is kept aside.
    ForEachRow(model.rows, model.cols, threads, [&](NodeRange row) {
      Kick(row, half, model.inverse_mass, Arrays(forces_), Velocities(*state), Arrays(&half_v_));
      Drift(row, step, Arrays(half_v_), Positions(*state), Positions(state));
      Kick(row, step, model.inverse_mass, Arrays(forces_), Velocities(*state), Velocities(state));
    });
    state->time += h;
    Evaluate(context, *state, state->time);
    ForEachRow(model.rows, model.cols, threads, [&](NodeRange row) {
      Kick(row, half, model.inverse_mass, Arrays(forces_), Arrays(half_v_), Velocities(state));
    });
  }

  double StableStep(const FrequencyBound& bound) const override {
    const double w2 = bound.omega_squared, g = bound.damping_rate;
    if (w2 <= 0 && g <= 0) return std::numeric_limits<double>::infinity();
    return 2 / (g + std::sqrt(g * g + w2));
  }

  void Reset() override { have_forces_ = false; }

  NodeVectors<Real> Memory() const override {
    if (!have_forces_) return {};
    return {forces_.x, forces_.y, forces_.z};
  }

  void Recall(const NodeVectors<Real>& memory) override {
    have_forces_ = !memory.x.empty();
    forces_ = {memory.x, memory.y, memory.z};
    half_v_.Resize(int(memory.x.size()));
  }

 private:
  void Evaluate(const StepContext<Real>& context, const ClothState<Real>& state, double t) {
    context.evaluator.Evaluate(context.model, context.params, context.wind, state, t, &forces_);
    half_v_.Resize(context.model.num_nodes());
    have_forces_ = true;
  }

  bool have_forces_ = false;
  NodeForces<Real> forces_;   ///< F at the end of the last substep
  NodeVectors<Real> half_v_;  ///< m/s, v' = v + h/2 a_n
};

}  // namespace

template <typename Real>
std::unique_ptr<Integrator<Real>> MakeVelocityVerlet() {
  return std::make_unique<VelocityVerlet<Real>>();
}
template std::unique_ptr<Integrator<float>> MakeVelocityVerlet<float>();
template std::unique_ptr<Integrator<double>> MakeVelocityVerlet<double>();

}  // namespace flagsim::sim
