#include "server/lab/stability.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <vector>

#include "server/sim/cloth_model.hpp"

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

// K (or C) at rest: each spring adds s u u^T to its nodes' diagonal blocks and -s u u^T off the
// diagonal (u its unit direction, s its stiffness or damping); the mass-weighted form
// M^-1/2 K M^-1/2 is symmetric with the eigenvalues of M^-1 K.
double TopEigenvalue(const sim::SimParams& params, bool of_damping) {
  const sim::ClothModel<double> model = sim::BuildClothModel<double>(params);
  std::vector<int> slot(model.num_nodes(), -1);  // free node => its block in the matrix
  int free_nodes = 0;
  for (int i = 0; i < model.num_nodes(); ++i) {
    if (!model.pinned(i)) slot[i] = free_nodes++;
  }
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(3 * free_nodes, 3 * free_nodes);
  const auto add = [&](int a, int b, const Eigen::Matrix3d& block) {
    if (slot[a] < 0 || slot[b] < 0) return;
    k.block<3, 3>(3 * slot[a], 3 * slot[b]) += block;
  };
  for (const sim::SpringFamily<double>& family : model.families) {
    for (int r = 0; r + family.dr < model.rows; ++r) {
      for (int c = family.first_col(); c < family.end_col(model.cols); ++c) {
        const int a = model.index(r, c), b = model.index(r + family.dr, c + family.dc);
        const Eigen::Vector3d u =
            Eigen::Vector3d(model.rest_x[b] - model.rest_x[a], model.rest_y[b] - model.rest_y[a],
                            model.rest_z[b] - model.rest_z[a])
                .normalized();
        const Eigen::Matrix3d block = (of_damping ? family.damping : family.stiffness) * u * u.transpose();
        add(a, a, block);
        add(b, b, block);
        add(a, b, -block);
        add(b, a, -block);
      }
    }
  }
  Eigen::VectorXd scale(3 * free_nodes);
  for (int i = 0; i < model.num_nodes(); ++i) {
    if (slot[i] >= 0) scale.segment<3>(3 * slot[i]).setConstant(1 / std::sqrt(model.mass[i]));
  }
  const Eigen::MatrixXd weighted = scale.asDiagonal() * k * scale.asDiagonal();
  const Eigen::VectorXd eigenvalues = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(weighted).eigenvalues();
  return std::max(eigenvalues.maxCoeff(), 0.0);
}

}  // namespace flagsim::lab
