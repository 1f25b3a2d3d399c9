// Explicit (forward) Euler: both updates read the state at the start of the substep.
//   x <- x + h v;  v <- v + h M^-1 F(x, v, t)
// Stability: on x'' = -w^2 x - g x' a substep multiplies each mode by 1 + h s, s a root of
// s^2 + g s + w^2 = 0. An underdamped mode shrinks only if |1 + h s|^2 = 1 - h g + h^2 w^2 < 1,
// that is h < g / w^2; an overdamped one if h < 2 / |s|, |s| <= g. Every mode's damping is at
// least ratio w^2 + friction (FrequencyBound), so h < ratio + friction / w_max^2 and
// h < 2 / g_max suffice. Without damping no step is stable: the method's classic failure.
#include <algorithm>
#include <cmath>
#include <limits>

#include "server/sim/integrator.hpp"
#include "server/sim/node_update.hpp"

namespace flagsim::sim {
namespace {

template <typename Real>
class ExplicitEuler : public Integrator<Real> {
 public:
  void Substep(const StepContext<Real>& context, double h, ClothState<Real>* state) override {
    const ClothModel<Real>& model = context.model;
    context.evaluator.Evaluate(model, context.params, context.wind, *state, state->time, &forces_);
    const Real step = Real(h);
    ForEachRow(model.rows, model.cols, context.params.threads, [&](NodeRange row) {
      Drift(row, step, Velocities(*state), Positions(*state), Positions(state));  // with the old v
      Kick(row, step, model.inverse_mass, Arrays(forces_), Velocities(*state), Velocities(state));
    });
    state->time += h;
  }

  double StableStep(const FrequencyBound& bound) const override {
    const double w2 = bound.omega_squared, g = bound.damping_rate;
    double limit = std::numeric_limits<double>::infinity();
    if (w2 > 0) limit = bound.stiffness_damping_ratio + bound.friction / w2;
    if (g > 0) limit = std::min(limit, 2 / g);
    return limit;
  }

 private:
  NodeForces<Real> forces_;
};

}  // namespace

template <typename Real>
std::unique_ptr<Integrator<Real>> MakeExplicitEuler() {
  return std::make_unique<ExplicitEuler<Real>>();
}
template std::unique_ptr<Integrator<float>> MakeExplicitEuler<float>();
template std::unique_ptr<Integrator<double>> MakeExplicitEuler<double>();

}  // namespace flagsim::sim
