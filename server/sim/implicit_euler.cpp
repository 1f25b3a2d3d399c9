// Implicit (backward) Euler, linearised once per substep (Baraff and Witkin 1998):
//   (M - h dF/dv - h^2 dF/dx) dv = h (F + h dF/dx v),  v <- v + dv,  x <- x + h v
// F = F(x, v, t) is the full force law (forces.hpp); the Jacobians are the springs' and the air
// friction's (spring_jacobian.hpp), so wind enters only through F. The system is solved by
// block-Jacobi preconditioned conjugate gradient (conjugate_gradient.hpp) to
// params.solver_tolerance relative residual, at most kMaxIterations iterations, starting from the
// previous substep's dv (Reset forgets it). Pinned nodes are filtered out of the system: dv = 0.
// Order 1; on linear springs unconditionally stable, and it damps every mode, the stiffest most.
#include <limits>

#include "server/parallel/worker_pool.hpp"
#include "server/sim/conjugate_gradient.hpp"
#include "server/sim/integrator.hpp"
#include "server/sim/spring_jacobian.hpp"

namespace flagsim::sim {
namespace {

/// Conjugate gradient iterations per substep at most. The default flag at 2 ms needs tens; a
/// stiff flag at large steps is far worse conditioned (k = 1e5 N/m at 1/60 s on 64 x 48 nodes needs
/// about 2000 for 1e-3), and cut off at 200 its steps gain energy, at 1000 they still lose it.
constexpr int kMaxIterations = 1000;

template <typename Real>
class ImplicitEuler : public Integrator<Real> {
 public:
  void Substep(const StepContext<Real>& context, double h, ClothState<Real>* state) override {
    const ClothModel<Real>& model = context.model;
    const SimParams& params = context.params;
    context.evaluator.Evaluate(model, params, context.wind, *state, state->time, &forces_);
    jacobian_.Assemble(model, *state, forces_, h, AirFriction(params), params.threads, &rhs_);
    jacobian_.Filter(&dv_);  // the first guess must not move pinned nodes either
    solver_.Solve(jacobian_, rhs_, params.solver_tolerance, kMaxIterations, params.threads, &dv_);
    const Real step = Real(h);
    const int rows = model.rows, cols = model.cols;
    ParallelFor(rows, params.threads, [&](int r) {
      for (int i = r * cols; i < (r + 1) * cols; ++i) {
        state->vx[i] += dv_.x[i];
        state->vy[i] += dv_.y[i];
        state->vz[i] += dv_.z[i];
        state->x[i] += step * state->vx[i];
        state->y[i] += step * state->vy[i];
        state->z[i] += step * state->vz[i];
      }
    });
    state->time += h;
  }

  double StableStep(const FrequencyBound&) const override { return std::numeric_limits<double>::infinity(); }

  void Reset() override { dv_.SetZero(); }
  NodeVectors<Real> Memory() const override { return dv_; }
  void Recall(const NodeVectors<Real>& memory) override { dv_ = memory; }

 private:
  NodeForces<Real> forces_;
  SpringJacobian<Real> jacobian_;
  ConjugateGradient<Real> solver_;
  NodeVectors<Real> rhs_;
  NodeVectors<Real> dv_;  ///< the last substep's, the next solve's first guess
};

}  // namespace

template <typename Real>
std::unique_ptr<Integrator<Real>> MakeImplicitEuler() {
  return std::make_unique<ImplicitEuler<Real>>();
}
template std::unique_ptr<Integrator<float>> MakeImplicitEuler<float>();
template std::unique_ptr<Integrator<double>> MakeImplicitEuler<double>();

}  // namespace flagsim::sim
