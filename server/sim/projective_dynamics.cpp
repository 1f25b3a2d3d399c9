// Projective dynamics for mass-spring systems (Liu, Bargteil, O'Brien and Kavan 2013, "Fast
// simulation of mass-spring systems"): backward Euler solved by local/global iterations.
//
// The physics it steps:
//   M (x' - x - h v) / h^2 = f_s(x') + f_ext - friction M v' - C v',   v' = (x' - x) / h
// f_s the springs' elastic forces k (|d| - L) u as in forces.hpp and the bending's -B Q x'
// - beta B Q v' (bending.hpp; linear, so it sits in the global matrix whole, and its elastic force
// at x in f_ext: -B Q x' = -B Q x - B Q dx); f_ext gravity and wind, both at
// (x, v, t) (relative wind sees v), held through the step; friction at the end of the step (as
// forces.hpp's law, but implicit). Spring damping, forces.hpp's c ((v_b - v_a) . u) u, is split
// so that the matrix stays constant: C is an isotropic damping Laplacian (each spring pulls its
// ends with c (v'_b - v'_a), implicit), and f_ext also carries the difference between the law
// and it at the start of the step, -c (dv - (dv . u) u) with dv = v_b - v_a (explicit). The
// explicit part only removes damping across springs, C_perp <= C, so the split is as stable as
// the implicit damping alone: (M + h C) v' = (M + h C_perp) v has all eigenvalues in (0, 1].
// So the method steps the same ODE as the other integrators, to first order in h. Converged, the
// step is backward Euler on the springs; with params.solver_iterations iterations it is the
// iterate after that many, which leaves stiff springs somewhat softer than k (the method's known
// artefact).
//
// One substep, in displacements dx = x' - x (pinned nodes have dx = 0):
//   q = x + h v, the first iterate
//   repeat params.solver_iterations times:
//     local   per spring a -> b, e = q_b - q_a: p = l e / |e|, the spring at length l along the
//             iterate (l = L when |e| >= L; see below when |e| < L), and t = k (d - p) with
//             d = x_b - x_a, the start of the step
//     global  A dx = h M v + h^2 f_ext + h^2 J t,  (J t)_a = sum of t over springs from a minus
//             sum over springs into a;  q = x + dx
//   x' = q, v' = dx / h
// with A = (1 + h friction) M + h C + h^2 L (spring_laplacian.hpp), constant over steps and so
// factorised once. This is Liu et al.'s global step A x' = M y + h friction M x + h C x + h^2 J p
// (f_s(x') ~ J p - L x', y = x + h v + h^2 M^-1 f_ext) with A x subtracted from both sides:
// friction and damping act on dx alone, and J t = J p - L x. Each iteration lowers the step's
// objective; starting from x + h v (not y) makes a state at rest after a step one the iteration
// cannot lower, so rest states are exact force balances (f_s + f_ext = 0) even with few
// iterations. Starting from y, a stiff flag would come to rest short of its equilibrium.
//
// Compressed springs (Choi and Ko 2002's stretch/compression split): a spring with |e| < L has
// the energy E(e) = k_c (|e| - L)^2 / 2, k_c = compression k <= k, while the global step's matrix
// is built once from k. The local step picks the target whose quadratic k |e' - p|^2 / 2 has
// E's gradient at the iterate e: k (e - p) = k_c (|e| - L) e / |e|, so
//   p = l e / |e|,  l = |e| - (k_c / k) (|e| - L) = L + slack (|e| - L),  slack = 1 - k_c / k,
// a spring relaxed part of the way from its rest length to its current one. For a stretched
// spring slack = 0 and p = L e / |e|, Liu et al.'s projection, which is the same rule. Since E's
// Hessian is at most k I in either regime (k_c (u u^T + (1 - L / |e|)(I - u u^T)), the transverse
// term negative), the quadratic lies above E and touches it at e; so each iteration still lowers
// the step's objective, and converged, the step is backward Euler on the piecewise spring: the
// fixed matrix sees k_c as the compressed spring's effective stiffness.
// Springs and gathers run row-parallel with each node summing its own springs in a fixed order;
// the solve runs one coordinate per thread: results do not depend on the thread count.
#include <algorithm>
#include <cmath>
#include <limits>

#include "server/parallel/worker_pool.hpp"
#include "server/sim/bending.hpp"
#include "server/sim/integrator.hpp"
#include "server/sim/node_update.hpp"
#include "server/sim/spring_laplacian.hpp"
#include "server/sim/spring_runs.hpp"

namespace flagsim::sim {
namespace {

/// Springs a -> a + offset for a in [begin, end): t = k (d - l e / |e|), d from the step's start
/// positions (x, y, z), e from the iterate (px, py, pz), l = L + slack (|e| - L) when |e| < L
/// and L otherwise (the top of this file).
template <typename Real>
void SpringTargetKernel(const Real* __restrict x, const Real* __restrict y, const Real* __restrict z,
                        const Real* __restrict px, const Real* __restrict py, const Real* __restrict pz,
                        Real* __restrict tx, Real* __restrict ty, Real* __restrict tz, int begin, int end,
                        int offset, Real k, Real rest, Real slack) {
  for (int a = begin; a < end; ++a) {
    const int b = a + offset;
    const Real ex = px[b] - px[a], ey = py[b] - py[a], ez = pz[b] - pz[a];
    const Real length = std::max(std::sqrt(ex * ex + ey * ey + ez * ez), Real(kShortestSpring));
    const Real give = length < rest ? slack : Real(0);
    const Real scale = (rest + give * (length - rest)) / length;
    tx[a] = k * ((x[b] - x[a]) - scale * ex);
    ty[a] = k * ((y[b] - y[a]) - scale * ey);
    tz[a] = k * ((z[b] - z[a]) - scale * ez);
  }
}

/// Springs a -> a + offset for a in [begin, end): t = -c (dv - (dv . d) d / |d|^2), dv = v_b - v_a,
/// the force on a that turns the isotropic damping c dv, which the solve applies, into the spring
/// law's c (dv . u) u (its far node gets -t).
template <typename Real>
void TransverseDampingKernel(const Real* __restrict x, const Real* __restrict y, const Real* __restrict z,
                             const Real* __restrict vx, const Real* __restrict vy, const Real* __restrict vz,
                             Real* __restrict tx, Real* __restrict ty, Real* __restrict tz, int begin,
                             int end, int offset, Real damping) {
  for (int a = begin; a < end; ++a) {
    const int b = a + offset;
    const Real dx = x[b] - x[a], dy = y[b] - y[a], dz = z[b] - z[a];
    const Real dvx = vx[b] - vx[a], dvy = vy[b] - vy[a], dvz = vz[b] - vz[a];
    const Real length_squared =
        std::max(dx * dx + dy * dy + dz * dz, Real(kShortestSpring * kShortestSpring));
    const Real along = (dvx * dx + dvy * dy + dvz * dz) / length_squared;
    tx[a] = -damping * (dvx - along * dx);
    ty[a] = -damping * (dvy - along * dy);
    tz[a] = -damping * (dvz - along * dz);
  }
}

/// out[a] += sign t[a + shift] for a in [begin, end).
template <typename Real>
void GatherKernel(const Real* __restrict tx, const Real* __restrict ty, const Real* __restrict tz,
                  Real* __restrict outx, Real* __restrict outy, Real* __restrict outz, int begin, int end,
                  int shift, Real sign) {
  for (int a = begin; a < end; ++a) {
    outx[a] += sign * tx[a + shift];
    outy[a] += sign * ty[a + shift];
    outz[a] += sign * tz[a + shift];
  }
}

/// 1 - k_c / k: how far a compressed spring's target relaxes towards its current length; 0 for a
/// spring with no stiffness (it has no target to move).
template <typename Real>
Real CompressionSlack(const SpringFamily<Real>& family) {
  return family.stiffness > 0 ? Real(1) - family.compression_stiffness / family.stiffness : Real(0);
}

template <typename Real>
class ProjectiveDynamics : public Integrator<Real> {
 public:
  void Substep(const StepContext<Real>& context, double h, ClothState<Real>* state) override {
    const ClothModel<Real>& model = context.model;
    const SimParams& params = context.params;
    laplacian_.Prepare(model, h, AirFriction(params));
    ExternalForces(context, *state);
    AddBendingForce(model, *state, params.threads);
    AddDampingCorrection(model, params, *state);
    Predict(model, params, *state, Real(h));
    for (int i = 0; i < params.solver_iterations; ++i) {
      if (i > 0) MoveIterate(model, *state, params.threads);
      RightHandSide(model, params, *state, Real(h));
      laplacian_.Solve(rhs_, params.threads, &displacement_);
    }
    Finish(model, Real(h), params.threads, state);
    state->time += h;
  }

  double StableStep(const FrequencyBound&) const override { return std::numeric_limits<double>::infinity(); }

  void Reset() override { laplacian_.Clear(); }

 private:
  /// Gravity and wind at the step's start: every force but the springs' and friction (the
  /// global step's matrix holds both).
  void ExternalForces(const StepContext<Real>& context, const ClothState<Real>& state) {
    context.evaluator.Evaluate(context.model, context.params, context.wind, state, state.time, &forces_,
                               ForceTerms::kGravity | ForceTerms::kWind);
  }

  /// Adds the bending's elastic force at the step's start, -B Q x, to f_ext (the matrix holds the
  /// rest of it, -B Q dx, and its damping).
  void AddBendingForce(const ClothModel<Real>& model, const ClothState<Real>& state, int threads) {
    if (model.bending_stiffness == Real(0)) return;
    const int pad = BendingPadding(model.cols), n = model.num_nodes();
    curvature_.assign(n + 2 * pad, Real(0));
    bending_.resize(n);
    const Real* positions[3] = {state.x.data(), state.y.data(), state.z.data()};
    Real* forces[3] = {forces_.x.data(), forces_.y.data(), forces_.z.data()};
    for (int k = 0; k < 3; ++k) {
      ParallelFor(model.rows, threads,
                  [&](int r) { CurvatureRows(model, positions[k], static_cast<const Real*>(nullptr), r, r + 1, curvature_.data() + pad); });
      ParallelFor(model.rows, threads, [&](int r) {
        BendingForceRows(model, curvature_.data() + pad, r, r + 1, bending_.data());
        for (int i = r * model.cols; i < (r + 1) * model.cols; ++i) forces[k][i] += bending_[i];
      });
    }
  }

  /// Adds the explicit part of the spring damping to f_ext (see the top of this file): every
  /// spring's t into targets_ (free until the iterations start), then each node sums its own.
  void AddDampingCorrection(const ClothModel<Real>& model, const SimParams& params,
                            const ClothState<Real>& state) {
    const int rows = model.rows;
    targets_.resize(model.families.size());
    for (NodeVectors<Real>& family : targets_) family.Resize(model.num_nodes());
    ParallelFor(rows, params.threads, [&](int r) { TransverseDampingRow(model, state, r); });
    ParallelFor(rows, params.threads, [&](int r) {
      ForEachSpringRun(model, r, [&](const SpringRun& run) {
        const NodeVectors<Real>& t = targets_[run.family];
        GatherKernel(t.x.data(), t.y.data(), t.z.data(), forces_.x.data(), forces_.y.data(), forces_.z.data(),
                     run.begin, run.end, run.spring_shift, run.first ? Real(1) : Real(-1));
      });
    });
  }

  void TransverseDampingRow(const ClothModel<Real>& model, const ClothState<Real>& state, int r) {
    for (size_t f = 0; f < model.families.size(); ++f) {
      const SpringFamily<Real>& family = model.families[f];
      if (r + family.dr >= model.rows) continue;
      NodeVectors<Real>& t = targets_[f];
      TransverseDampingKernel(state.x.data(), state.y.data(), state.z.data(), state.vx.data(),
                              state.vy.data(), state.vz.data(), t.x.data(), t.y.data(), t.z.data(),
                              model.index(r, family.first_col()), model.index(r, family.end_col(model.cols)),
                              family.dr * model.cols + family.dc, family.damping);
    }
  }

  /// The first iterate x + h v, and the constant part of the right-hand side, h M v + h^2 f_ext
  /// (0 at pinned nodes).
  void Predict(const ClothModel<Real>& model, const SimParams& params, const ClothState<Real>& state,
               Real h) {
    const int n = model.num_nodes();
    iterate_.Resize(n);
    momentum_.Resize(n);
    rhs_.Resize(n);
    ForEachRow(model.rows, model.cols, params.threads, [&](NodeRange row) {
      for (int i = row.begin; i < row.end; ++i) {
        const Real free = model.pinned(i) ? Real(0) : Real(1);
        momentum_.x[i] = free * (h * model.mass[i] * state.vx[i] + h * h * forces_.x[i]);
        momentum_.y[i] = free * (h * model.mass[i] * state.vy[i] + h * h * forces_.y[i]);
        momentum_.z[i] = free * (h * model.mass[i] * state.vz[i] + h * h * forces_.z[i]);
        iterate_.x[i] = state.x[i] + h * state.vx[i];
        iterate_.y[i] = state.y[i] + h * state.vy[i];
        iterate_.z[i] = state.z[i] + h * state.vz[i];
      }
    });
  }

  /// Local step (every spring's t at the iterate), then each row gathers h M v + h^2 f_ext + h^2 J t.
  void RightHandSide(const ClothModel<Real>& model, const SimParams& params, const ClothState<Real>& state,
                     Real h) {
    const int rows = model.rows;
    ParallelFor(rows, params.threads, [&](int r) { TargetRow(model, state, r); });
    ParallelFor(rows, params.threads, [&](int r) { GatherRow(model, h, r); });
  }

  void TargetRow(const ClothModel<Real>& model, const ClothState<Real>& state, int r) {
    for (size_t f = 0; f < model.families.size(); ++f) {
      const SpringFamily<Real>& family = model.families[f];
      if (r + family.dr >= model.rows) continue;
      NodeVectors<Real>& t = targets_[f];
      SpringTargetKernel(state.x.data(), state.y.data(), state.z.data(), iterate_.x.data(), iterate_.y.data(),
                         iterate_.z.data(), t.x.data(), t.y.data(), t.z.data(),
                         model.index(r, family.first_col()), model.index(r, family.end_col(model.cols)),
                         family.dr * model.cols + family.dc, family.stiffness, family.rest_length,
                         CompressionSlack(family));
    }
  }

  void GatherRow(const ClothModel<Real>& model, Real h, int r) {
    const int row = r * model.cols, end = row + model.cols;
    std::fill(rhs_.x.begin() + row, rhs_.x.begin() + end, Real(0));
    std::fill(rhs_.y.begin() + row, rhs_.y.begin() + end, Real(0));
    std::fill(rhs_.z.begin() + row, rhs_.z.begin() + end, Real(0));
    ForEachSpringRun(model, r, [&](const SpringRun& run) {
      const NodeVectors<Real>& t = targets_[run.family];
      GatherKernel(t.x.data(), t.y.data(), t.z.data(), rhs_.x.data(), rhs_.y.data(), rhs_.z.data(), run.begin,
                   run.end, run.spring_shift, run.first ? Real(1) : Real(-1));
    });
    for (int i = row; i < end; ++i) {
      const Real free = model.pinned(i) ? Real(0) : Real(1);
      rhs_.x[i] = momentum_.x[i] + free * h * h * rhs_.x[i];
      rhs_.y[i] = momentum_.y[i] + free * h * h * rhs_.y[i];
      rhs_.z[i] = momentum_.z[i] + free * h * h * rhs_.z[i];
    }
  }

  /// The next iterate, x + dx, at free nodes.
  void MoveIterate(const ClothModel<Real>& model, const ClothState<Real>& state, int threads) {
    ForEachRow(model.rows, model.cols, threads, [&](NodeRange row) {
      for (int i = row.begin; i < row.end; ++i) {
        if (model.pinned(i)) continue;
        iterate_.x[i] = state.x[i] + displacement_.x[i];
        iterate_.y[i] = state.y[i] + displacement_.y[i];
        iterate_.z[i] = state.z[i] + displacement_.z[i];
      }
    });
  }

  /// x' = x + dx, v' = dx / h at free nodes.
  void Finish(const ClothModel<Real>& model, Real h, int threads, ClothState<Real>* state) const {
    ForEachRow(model.rows, model.cols, threads, [&](NodeRange row) {
      for (int i = row.begin; i < row.end; ++i) {
        if (model.pinned(i)) continue;
        state->x[i] += displacement_.x[i];
        state->y[i] += displacement_.y[i];
        state->z[i] += displacement_.z[i];
        state->vx[i] = displacement_.x[i] / h;
        state->vy[i] = displacement_.y[i] / h;
        state->vz[i] = displacement_.z[i] / h;
      }
    });
  }

  SpringLaplacian<Real> laplacian_;
  NodeForces<Real> forces_;  ///< f_ext
  NodeVectors<Real> iterate_, momentum_, rhs_, displacement_;
  std::vector<Real> curvature_, bending_;  ///< one coordinate's, bending.hpp's layout
  std::vector<NodeVectors<Real>> targets_;  ///< t per spring, per family, at the spring's first node
};

}  // namespace

template <typename Real>
std::unique_ptr<Integrator<Real>> MakeProjectiveDynamics() {
  return std::make_unique<ProjectiveDynamics<Real>>();
}
template std::unique_ptr<Integrator<float>> MakeProjectiveDynamics<float>();
template std::unique_ptr<Integrator<double>> MakeProjectiveDynamics<double>();

}  // namespace flagsim::sim
