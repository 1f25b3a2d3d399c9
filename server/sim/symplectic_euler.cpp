// Symplectic (semi-implicit) Euler, and the seed's scheme, which is the same update with the
// seed's friction law.
//   v <- v + h M^-1 F(x, v, t);  x <- x + h v
// Stability on x'' = -w^2 x - g x' (the update matrix has trace 2 - h^2 w^2 - h g and
// determinant 1 - h g; Jury's test): h^2 w^2 + 2 h g < 4, so h < (sqrt(g^2 + 4 w^2) - g) / w^2,
// which is 2 / w without damping.
#include <cmath>
#include <limits>

#include "server/sim/integrator.hpp"
#include "server/sim/node_update.hpp"

namespace flagsim::sim {
namespace {

template <typename Real>
class SymplecticEuler : public Integrator<Real> {
 public:
  /// `seed_friction`: scale forces by the seed's 1 - mu (its friction F_fric = -mu F).
  explicit SymplecticEuler(bool seed_friction) : seed_friction_(seed_friction) {}

  void Substep(const StepContext<Real>& context, double h, ClothState<Real>* state) override {
    const ClothModel<Real>& model = context.model;
    const Real scale = seed_friction_ ? Real(1 - context.params.forces.friction) : Real(1);
    const Real step = Real(h);
    // Each row is updated as soon as its forces are summed, while they are in cache.
    const auto update_row = [&](int r) {
      const NodeRange row{r * model.cols, (r + 1) * model.cols};
      Kick(row, step * scale, model.inverse_mass, Arrays(forces_), Velocities(*state), Velocities(state));
      Drift(row, step, Velocities(*state), Positions(*state), Positions(state));  // with the new v
    };
    context.evaluator.Evaluate(model, context.params, context.wind, *state, state->time, &forces_,
                               ForceTerms::kAll, update_row);
    state->time += h;
  }

  double StableStep(const FrequencyBound& bound) const override {
    const double w2 = bound.omega_squared, g = bound.damping_rate;
    if (w2 <= 0) return std::numeric_limits<double>::infinity();
    return (std::sqrt(g * g + 4 * w2) - g) / w2;
  }

 private:
  bool seed_friction_;
  NodeForces<Real> forces_;
};

}  // namespace

template <typename Real>
std::unique_ptr<Integrator<Real>> MakeSymplecticEuler(bool seed_friction) {
  return std::make_unique<SymplecticEuler<Real>>(seed_friction);
}
template std::unique_ptr<Integrator<float>> MakeSymplecticEuler<float>(bool);
template std::unique_ptr<Integrator<double>> MakeSymplecticEuler<double>(bool);

}  // namespace flagsim::sim
