// The constant matrix of projective dynamics' global step, factorised once and reused:
//   A = (1 + h friction) M + h C + h^2 L + (h^2 + h beta) B Q
// over the nodes, one scalar matrix for x, y and z. L is the stiffness-weighted graph Laplacian
// (spring s between a and b adds k_s to A_aa and A_bb and -k_s to A_ab and A_ba), C the same with
// the damping constants c_s; B Q is the bending's (bending.hpp: f = -B Q (x + beta v), linear,
// so backward Euler on it is exact in the global step). Unknowns are displacements, so a pinned node's is 0: its row and
// column are the identity's and its springs add only to their free end's diagonal.
// Factorised by sparse LDL^T (Eigen's SimplicialLDLT, AMD ordering), again only when h, friction,
// the grid, the spring constants, the bending or the masses change (or after Clear).
#pragma once

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <vector>

#include "server/sim/cloth_model.hpp"
#include "server/sim/node_vectors.hpp"

namespace flagsim::sim {

template <typename Real>
class SpringLaplacian {
 public:
  /// Factorises A for (model, h, friction) unless the factorisation in hand is of the same A.
  void Prepare(const ClothModel<Real>& model, double h, double friction);
  /// Forgets the factorisation: the next Prepare factorises.
  void Clear() { factorised_ = false; }

  /// x = A^-1 b for the three coordinates, one per thread if `threads` > 1.
  void Solve(const NodeVectors<Real>& b, int threads, NodeVectors<Real>* x) const;

 private:
  bool Current(const ClothModel<Real>& model, double h, double friction) const;
  void Factorise(const ClothModel<Real>& model);

  using Matrix = Eigen::SparseMatrix<Real>;
  Eigen::SimplicialLDLT<Matrix> factorisation_;
  bool factorised_ = false;
  // What A was built from: the cache key.
  double h_ = 0, friction_ = 0;
  int cols_ = 0, rows_ = 0;
  std::vector<SpringFamily<Real>> families_;
  Real bending_stiffness_ = 0, bending_damping_ = 0;
  std::vector<Real> mass_, inverse_mass_;
};

}  // namespace flagsim::sim
