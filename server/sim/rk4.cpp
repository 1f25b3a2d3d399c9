// Classic fourth-order Runge-Kutta on y = (x, v), y' = (v, M^-1 F(x, v, t)):
//   k1 = f(t, y),  k2 = f(t + h/2, y + h/2 k1),  k3 = f(t + h/2, y + h/2 k2),  k4 = f(t + h, y + h k3)
//   y <- y + h/6 (k1 + 2 k2 + 2 k3 + k4)
// Each stage's derivative is (its velocity, its acceleration), so a stage keeps a whole state;
// the weighted sums of velocities and forces build up as the stages go.
// Stability: the region |1 + z + z^2/2 + z^3/6 + z^4/24| <= 1 holds the left half disc of
// radius 2.61 (2.83 on the imaginary axis, 2.79 on the real one; the disc is what is left
// between). Every mode's eigenvalues s of x'' = -w^2 x - g x' have |s| <= max(w, g), so
// h < 2.61 / max(w_max, g_max).
#include <algorithm>
#include <cmath>
#include <limits>

#include "server/sim/integrator.hpp"
#include "server/sim/node_update.hpp"
#include "server/sim/node_vectors.hpp"

namespace flagsim::sim {
namespace {

constexpr double kHalfDiscRadius = 2.61;

template <typename Real>
class Rk4 : public Integrator<Real> {
 public:
  void Substep(const StepContext<Real>& context, double h, ClothState<Real>* state) override {
    const ClothModel<Real>& model = context.model;
    Resize(model.num_nodes());
    stage_ = *state;
    const double t = state->time;
    // (stage time, weight of its derivative in the sum, step to the next stage's state)
    const struct {
      double at, weight, next;
    } stages[4] = {{0, 1, h / 2}, {h / 2, 2, h / 2}, {h / 2, 2, h}, {h, 1, 0}};
    for (int s = 0; s < 4; ++s) {
      context.evaluator.Evaluate(model, context.params, context.wind, stage_, t + stages[s].at, &forces_);
      Accumulate(model, context.params.threads, Real(stages[s].weight), s == 0, *state, Real(stages[s].next));
    }
    Finish(model, context.params.threads, Real(h / 6), state);
    state->time = t + h;
  }

  double StableStep(const FrequencyBound& bound) const override {
    const double fastest = std::max(std::sqrt(bound.omega_squared), bound.damping_rate);
    return fastest > 0 ? kHalfDiscRadius / fastest : std::numeric_limits<double>::infinity();
  }

 private:
  void Resize(int n) {
    for (NodeVectors<Real>* vectors : {&sum_v_, &sum_f_, &zero_}) vectors->Resize(n);
  }

  // sums += weight (stage v, stage F), from 0 at the first stage; then the stage becomes
  // base + next (v, M^-1 F).
  void Accumulate(const ClothModel<Real>& model, int threads, Real weight, bool first,
                  const ClothState<Real>& base, Real next) {
    ForEachRow(model.rows, model.cols, threads, [&](NodeRange row) {
      Drift(row, weight, Velocities(stage_), Arrays(first ? zero_ : sum_v_), Arrays(&sum_v_));
      Drift(row, weight, Arrays(forces_), Arrays(first ? zero_ : sum_f_), Arrays(&sum_f_));
      Drift(row, next, Velocities(stage_), Positions(base), Positions(&stage_));
      Kick(row, next, model.inverse_mass, Arrays(forces_), Velocities(base), Velocities(&stage_));
    });
  }

  // y <- y + h/6 sums.
  void Finish(const ClothModel<Real>& model, int threads, Real sixth, ClothState<Real>* state) {
    ForEachRow(model.rows, model.cols, threads, [&](NodeRange row) {
      Drift(row, sixth, Arrays(sum_v_), Positions(*state), Positions(state));
      Kick(row, sixth, model.inverse_mass, Arrays(sum_f_), Velocities(*state), Velocities(state));
    });
  }

  ClothState<Real> stage_;
  NodeForces<Real> forces_;
  NodeVectors<Real> sum_v_;  ///< m/s, the weighted sum of the stages' velocities
  NodeVectors<Real> sum_f_;  ///< N, the weighted sum of the stages' forces
  NodeVectors<Real> zero_;   ///< what the sums start from
};

}  // namespace

template <typename Real>
std::unique_ptr<Integrator<Real>> MakeRk4() {
  return std::make_unique<Rk4<Real>>();
}
template std::unique_ptr<Integrator<float>> MakeRk4<float>();
template std::unique_ptr<Integrator<double>> MakeRk4<double>();

}  // namespace flagsim::sim
