// XPBD (Macklin, Mueller, Chentanez 2016): springs as compliant distance constraints, every
// other force (gravity, friction, wind) explicit.
//   v~ = v + h M^-1 F_ext(x, v, t);  p = x + h v~;  lambda = 0
//   solver_iterations times, each spring (a, b) in turn, with n = (p_b - p_a) / |p_b - p_a|:
//     C = |p_b - p_a| - L,  alpha~ = 1 / (k h^2),  gamma = c / (k h)
//     dl = (-C - alpha~ lambda - gamma n . ((p_b - x_b) - (p_a - x_a))) / ((1 + gamma)(w_a + w_b) + alpha~)
//     p_a -= w_a n dl;  p_b += w_b n dl;  lambda += dl
//     then each interior node j in turn (the bending, bending.hpp), with its stencil s_j:
//     C = sum_m s_m p_m (a 3-vector: the curvature), alpha~ = 1 / (B A h^2), gamma = beta / h
//     dl = (-C - alpha~ lambda_j - gamma sum_m s_m (p_m - x_m)) / ((1 + gamma) sum_m w_m s_m^2 + alpha~)
//     p_m += w_m s_m dl;  lambda_j += dl
//   v = (p - x) / h;  x = p
// Compliance 1/k makes the constraint the spring k (|d| - L) of forces.hpp and gamma its damping
// c along the spring, so that with enough iterations a step approaches implicit Euler on the
// same forces: first order, unconditionally stable, damping motion at large h. As in forces.hpp,
// k is the spring's compression stiffness when C < 0 (Choi and Ko 2002): each projection takes
// alpha~ and gamma of the regime the constraint is in at that moment, so the iteration's fixed
// point is the force balance of the piecewise spring. A spring with no stiffness in a regime is
// no constraint there (as a family with no stiffness is none at all).
// Gauss-Seidel in a fixed order that threads cannot change: each family's springs are split
// into two colours in which no two springs share a node (alternate columns of a family along
// the rows, alternate rows of one down the columns; in blocks of the family's reach), so the
// springs of one colour are solved in parallel and the colours one after another. The bending's
// stencils reach one node either way, so nodes three rows and three columns apart never share a
// node: nine colours by (r mod 3, c mod 3), the rows of one colour in parallel.
#include <cmath>
#include <limits>

#include "server/sim/bending.hpp"
#include "server/sim/integrator.hpp"
#include "server/sim/node_update.hpp"

namespace flagsim::sim {
namespace {

/// A spring's colour: 0 or 1 by the block of its first node along the family's direction.
template <typename Real>
int Colour(const SpringFamily<Real>& family, int r, int c) {
  return family.dr == 0 ? (c / family.dc) % 2 : (r / family.dr) % 2;
}

template <typename Real>
class Xpbd : public Integrator<Real> {
 public:
  void Substep(const StepContext<Real>& context, double h, ClothState<Real>* state) override {
    const ClothModel<Real>& model = context.model;
    context.evaluator.Evaluate(model, context.params, context.wind, *state, state->time, &forces_,
                               Without(ForceTerms::kAll, ForceTerms::kSprings | ForceTerms::kBending));
    Predict(model, context.params.threads, Real(h), state);
    lambda_.resize(model.families.size());
    for (std::vector<Real>& lambda : lambda_) lambda.assign(model.num_nodes(), Real(0));
    for (std::vector<Real>* lambda : {&bending_x_, &bending_y_, &bending_z_}) lambda->assign(model.num_nodes(), Real(0));
    Solve(model, context.params, Real(h), *state);
    Finish(model, context.params.threads, Real(h), state);
    state->time += h;
  }

  double StableStep(const FrequencyBound&) const override { return std::numeric_limits<double>::infinity(); }

 private:
  // v~ = v + h M^-1 F_ext, in the state's velocities until Finish replaces them; p = x + h v~.
  void Predict(const ClothModel<Real>& model, int threads, Real h, ClothState<Real>* state) {
    for (std::vector<Real>* p : {&px_, &py_, &pz_}) p->resize(model.num_nodes());
    const NodeArrays<Real> predicted{px_.data(), py_.data(), pz_.data()};
    ForEachRow(model.rows, model.cols, threads, [&](NodeRange row) {
      Kick(row, h, model.inverse_mass, Arrays(forces_), Velocities(*state), Velocities(state));
      Drift(row, h, Velocities(*state), Positions(*state), predicted);
    });
  }

  void Solve(const ClothModel<Real>& model, const SimParams& params, Real h, const ClothState<Real>& start) {
    for (int iteration = 0; iteration < params.solver_iterations; ++iteration) {
      for (size_t f = 0; f < model.families.size(); ++f) {
        for (int colour = 0; colour < 2; ++colour) {
          ParallelFor(model.rows - model.families[f].dr, params.threads, [&](int r) {
            SolveRow(model, model.families[f], lambda_[f].data(), r, colour, h, start);
          });
        }
      }
      if (model.bending_stiffness > Real(0)) SolveBending(model, params.threads, h, start);
    }
  }

  // Every interior node's bending constraint, colour by colour (the top of this file).
  void SolveBending(const ClothModel<Real>& model, int threads, Real h, const ClothState<Real>& start) {
    for (int row_colour = 0; row_colour < 3; ++row_colour) {
      const int first_row = row_colour == 0 ? 3 : row_colour;  // interior rows only: r >= 1
      const int count = first_row < model.rows - 1 ? (model.rows - 2 - first_row) / 3 + 1 : 0;
      for (int column_colour = 0; column_colour < 3; ++column_colour) {
        ParallelFor(count, threads, [&](int k) {
          SolveBendingRow(model, first_row + 3 * k, column_colour == 0 ? 3 : column_colour, h, start);
        });
      }
    }
  }

  // The bending constraints of row r's interior nodes from column `first` on, every third.
  void SolveBendingRow(const ClothModel<Real>& model, int r, int first, Real h, const ClothState<Real>& start) {
    const Real area = model.dx * model.dy;
    const Real compliance = Real(1) / (model.bending_stiffness * area * h * h);
    const Real gamma = model.bending_damping / h;
    for (int c = first; c + 1 < model.cols; c += 3) {
      const BendingStencil s = StencilOf(model, r, c);
      Real weight = 0;  // sum_m w_m s_m^2
      for (int m = 0; m < 5; ++m) weight += model.inverse_mass[s.nodes[m]] * Real(s.weights[m] * s.weights[m]);
      if (weight == Real(0)) continue;
      const int j = s.nodes[0];
      const struct {
        std::vector<Real>& p;
        const std::vector<Real>& x;
        std::vector<Real>& lambda;
      } coordinates[3] = {{px_, start.x, bending_x_}, {py_, start.y, bending_y_}, {pz_, start.z, bending_z_}};
      for (const auto& coordinate : coordinates) {
        Real curvature = 0, moved = 0;
        for (int m = 0; m < 5; ++m) {
          const int node = s.nodes[m];
          curvature += Real(s.weights[m]) * (coordinate.p[node] - coordinate.p[j]);
          moved += Real(s.weights[m]) * (coordinate.p[node] - coordinate.x[node]);
        }
        const Real dl = (-curvature - compliance * coordinate.lambda[j] - gamma * moved) /
                        ((1 + gamma) * weight + compliance);
        coordinate.lambda[j] += dl;
        for (int m = 0; m < 5; ++m) {
          const int node = s.nodes[m];
          coordinate.p[node] += model.inverse_mass[node] * Real(s.weights[m]) * dl;
        }
      }
    }
  }

  /// A spring's constants as a constraint in one regime: alpha~ = 1 / (k h^2), gamma = c / (k h).
  struct Compliance {
    bool active = false;  ///< k > 0
    Real alpha = 0;       ///< m/(N s^2), time-scaled compliance alpha~
    Real gamma = 0;       ///< damping ratio of the constraint
  };
  static Compliance ComplianceOf(Real stiffness, Real damping, Real h) {
    if (!(stiffness > 0)) return {};
    return {true, Real(1) / (stiffness * h * h), damping / (stiffness * h)};
  }

  // The springs of one colour whose first node is in row r.
  void SolveRow(const ClothModel<Real>& model, const SpringFamily<Real>& family, Real* lambda, int r,
                int colour, Real h, const ClothState<Real>& start) {
    const Compliance stretched = ComplianceOf(family.stiffness, family.damping, h);
    const Compliance compressed = ComplianceOf(family.compression_stiffness, family.damping, h);
    if (!stretched.active && !compressed.active) return;
    for (int c = family.first_col(); c < family.end_col(model.cols); ++c) {
      if (Colour(family, r, c) != colour) continue;
      const int a = model.index(r, c), b = model.index(r + family.dr, c + family.dc);
      const Real wa = model.inverse_mass[a], wb = model.inverse_mass[b];
      if (wa + wb == Real(0)) continue;
      Real nx = px_[b] - px_[a], ny = py_[b] - py_[a], nz = pz_[b] - pz_[a];
      const Real length = std::sqrt(nx * nx + ny * ny + nz * nz);
      if (length == Real(0)) continue;  // no direction to push along
      const Compliance& regime = length < family.rest_length ? compressed : stretched;
      if (!regime.active) continue;
      const Real compliance = regime.alpha, gamma = regime.gamma;
      nx /= length;
      ny /= length;
      nz /= length;
      const Real moved = nx * ((px_[b] - start.x[b]) - (px_[a] - start.x[a])) +
                         ny * ((py_[b] - start.y[b]) - (py_[a] - start.y[a])) +
                         nz * ((pz_[b] - start.z[b]) - (pz_[a] - start.z[a]));
      const Real dl = (-(length - family.rest_length) - compliance * lambda[a] - gamma * moved) /
                      ((1 + gamma) * (wa + wb) + compliance);
      lambda[a] += dl;
      px_[a] -= wa * dl * nx;
      py_[a] -= wa * dl * ny;
      pz_[a] -= wa * dl * nz;
      px_[b] += wb * dl * nx;
      py_[b] += wb * dl * ny;
      pz_[b] += wb * dl * nz;
    }
  }

  // v = (p - x) / h; x = p
  void Finish(const ClothModel<Real>& model, int threads, Real h, ClothState<Real>* state) {
    const Real inverse_h = Real(1) / h;
    ForEachRow(model.rows, model.cols, threads, [&](NodeRange row) {
      for (int i = row.begin; i < row.end; ++i) {
        state->vx[i] = (px_[i] - state->x[i]) * inverse_h;
        state->vy[i] = (py_[i] - state->y[i]) * inverse_h;
        state->vz[i] = (pz_[i] - state->z[i]) * inverse_h;
        state->x[i] = px_[i];
        state->y[i] = py_[i];
        state->z[i] = pz_[i];
      }
    });
  }

  NodeForces<Real> forces_;
  std::vector<Real> px_, py_, pz_;         ///< m, predicted then corrected positions
  std::vector<std::vector<Real>> lambda_;  ///< per family, per first node: the spring's multiplier
  std::vector<Real> bending_x_, bending_y_, bending_z_;  ///< per node: its bending constraint's multiplier
};

}  // namespace

template <typename Real>
std::unique_ptr<Integrator<Real>> MakeXpbd() {
  return std::make_unique<Xpbd<Real>>();
}
template std::unique_ptr<Integrator<float>> MakeXpbd<float>();
template std::unique_ptr<Integrator<double>> MakeXpbd<double>();

}  // namespace flagsim::sim
