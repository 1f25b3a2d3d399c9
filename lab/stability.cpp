#include "lab/stability.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <vector>

#include "server/sim/bending.hpp"
#include "server/sim/cloth_model.hpp"
#include "server/sim/forces.hpp"

namespace flagsim::lab {
namespace {

bool StableAt(Trial trial, double h) {
  const int substeps = static_cast<int>(std::ceil(trial.horizon / h));
  trial.horizon = substeps * h;  // exactly h per substep
  return StateIsSound(RunFixed<double>(trial, substeps));
}

}  // namespace

double LargestStableStep(const Trial& trial, double low, double high, double precision) {
  if (StableAt(trial, high)) return high;
  if (!StableAt(trial, low)) return low;
  while (high / low > 1 + precision) {
    const double middle = std::sqrt(low * high);  // bisection in log h
    (StableAt(trial, middle) ? low : high) = middle;
  }
  return low;
}

namespace {

/// The free nodes' slots in a dense 3n x 3n matrix; -1 for pinned nodes.
struct FreeSlots {
  std::vector<int> slot;
  int count = 0;
  explicit FreeSlots(const sim::ClothModel<double>& model) : slot(model.num_nodes(), -1) {
    for (int i = 0; i < model.num_nodes(); ++i) {
      if (!model.pinned(i)) slot[i] = count++;
    }
  }
};

/// Adds `block` coupling nodes a and b (a pinned node's rows and columns are left out).
void AddBlock(const FreeSlots& free, int a, int b, const Eigen::Matrix3d& block, Eigen::MatrixXd* matrix) {
  if (free.slot[a] < 0 || free.slot[b] < 0) return;
  matrix->block<3, 3>(3 * free.slot[a], 3 * free.slot[b]) += block;
}

/// Adds constant B Q (x I3): each interior node j's A s_j s_j^T.
void AddBending(const sim::ClothModel<double>& model, const FreeSlots& free, double constant,
                Eigen::MatrixXd* matrix) {
  const double area = model.dx * model.dy;
  for (int r = 1; r + 1 < model.rows; ++r) {
    for (int c = 1; c + 1 < model.cols; ++c) {
      const sim::BendingStencil s = sim::StencilOf(model, r, c);
      for (int a = 0; a < 5; ++a) {
        for (int b = 0; b < 5; ++b) {
          AddBlock(free, s.nodes[a], s.nodes[b],
                   constant * area * s.weights[a] * s.weights[b] * Eigen::Matrix3d::Identity(), matrix);
        }
      }
    }
  }
}

/// M^-1/2 S M^-1/2 over the free coordinates.
Eigen::MatrixXd MassWeighted(const sim::ClothModel<double>& model, const FreeSlots& free, const Eigen::MatrixXd& s) {
  Eigen::VectorXd scale(3 * free.count);
  for (int i = 0; i < model.num_nodes(); ++i) {
    if (free.slot[i] >= 0) scale.segment<3>(3 * free.slot[i]).setConstant(1 / std::sqrt(model.mass[i]));
  }
  return scale.asDiagonal() * s * scale.asDiagonal();
}

/// K(x) and C(x) of the springs and the bending (not friction) at positions `state`.
void TangentMatrices(const sim::ClothModel<double>& model, const FreeSlots& free, const sim::ClothState<double>& state,
                     Eigen::MatrixXd* k, Eigen::MatrixXd* c) {
  *k = Eigen::MatrixXd::Zero(3 * free.count, 3 * free.count);
  *c = Eigen::MatrixXd::Zero(3 * free.count, 3 * free.count);
  for (const sim::SpringFamily<double>& family : model.families) {
    for (int r = 0; r + family.dr < model.rows; ++r) {
      for (int col = family.first_col(); col < family.end_col(model.cols); ++col) {
        const int a = model.index(r, col), b = model.index(r + family.dr, col + family.dc);
        const Eigen::Vector3d d(state.x[b] - state.x[a], state.y[b] - state.y[a], state.z[b] - state.z[a]);
        const double length = d.norm();
        if (length == 0) continue;
        const Eigen::Vector3d u = d / length;
        const Eigen::Matrix3d along = u * u.transpose();
        // The Hessian of k (|d| - L)^2 / 2 in the regime the spring is in.
        const double stiffness = length < family.rest_length ? family.compression_stiffness : family.stiffness;
        const Eigen::Matrix3d kb =
            stiffness * (along + (1 - family.rest_length / length) * (Eigen::Matrix3d::Identity() - along));
        const Eigen::Matrix3d cb = family.damping * along;
        for (auto [matrix, block] : {std::pair{k, kb}, std::pair{c, cb}}) {
          AddBlock(free, a, a, block, matrix);
          AddBlock(free, b, b, block, matrix);
          AddBlock(free, a, b, -block, matrix);
          AddBlock(free, b, a, -block, matrix);
        }
      }
    }
  }
  AddBending(model, free, model.bending_stiffness, k);
  AddBending(model, free, model.bending_damping * model.bending_stiffness, c);
}

}  // namespace

// The matrices at rest are the tangent ones there: every spring at its rest length, in the
// stretched regime, with no transverse term.
double TopEigenvalue(const sim::SimParams& params, bool of_damping) {
  const sim::ClothModel<double> model = sim::BuildClothModel<double>(params);
  const FreeSlots free(model);
  Eigen::MatrixXd k, c;
  TangentMatrices(model, free, sim::RestState(model), &k, &c);
  const Eigen::MatrixXd weighted = MassWeighted(model, free, of_damping ? c : k);
  const Eigen::VectorXd eigenvalues = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(weighted).eigenvalues();
  return std::max(eigenvalues.maxCoeff(), 0.0);
}

StiffestMode StiffestModeAt(const sim::SimParams& params, const sim::ClothState<double>& state) {
  const sim::ClothModel<double> model = sim::BuildClothModel<double>(params);
  const FreeSlots free(model);
  Eigen::MatrixXd k, c;
  TangentMatrices(model, free, state, &k, &c);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(MassWeighted(model, free, k));
  const Eigen::Index top = solver.eigenvalues().size() - 1;  // ascending order
  const Eigen::VectorXd mode = solver.eigenvectors().col(top);
  StiffestMode stiffest;
  stiffest.omega_squared = std::max(solver.eigenvalues()[top], 0.0);
  stiffest.damping_rate = mode.dot(MassWeighted(model, free, c) * mode) + sim::AirFriction(params);
  return stiffest;
}

}  // namespace flagsim::lab
