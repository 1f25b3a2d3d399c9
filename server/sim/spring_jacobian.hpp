// The linear system of one linearised backward-Euler substep (Baraff and Witkin 1998), matrix-free:
//   A dv = b,  A = M (1 + h friction) - h dF/dv - h^2 dF/dx,  b = h (F + h dF/dx v)
// with the springs' Jacobians, the bending's and the air friction's (wind is left out of the
// Jacobian).
//
// Spring s from node a to node b, d = x_b - x_a, u = d / |d|, alpha = max(0, 1 - L / |d|):
//   dF_a/dx_b = K = k [u u^T + alpha (I - u u^T)],  dF_a/dv_b = D = c u u^T,
//   dF_a/dx_a = -K,  dF_a/dv_a = -D  (and the same with a and b swapped).
// K is the exact derivative of forces.hpp's k (|d| - L) u except that the transverse term is
// clamped at zero for compressed springs, which keeps A positive definite; D leaves out the
// damping force's dependence on x. k is the spring's stiffness in the regime it is in: its
// compression stiffness when |d| < L (Choi and Ko 2002), where alpha = 0 and K = k u u^T; the
// Jacobian of the compressed regime's law, so the step stays the linearised backward Euler step
// of forces.hpp's forces. So every spring adds the symmetric block
//   B = h^2 K + h D = iso I + axial u u^T,  iso = h^2 k alpha,  axial = h^2 k (1 - alpha) + h c,
// coupling a and b like a graph Laplacian, and
//   (A p)_a = m_a (1 + h friction) p_a + sum over springs s at a of B_s (p_a - p_other),
//   b_a     = h F_a - sum over springs s at a of h^2 K_s (v_a - v_other),
// where h^2 K = iso I + axial_stiffness u u^T, axial_stiffness = h^2 k (1 - alpha).
//
// Data flow: Assemble stores every block in that factored form (u, iso, axial, axial_stiffness:
// six numbers, the 3x3 block's six), per family, indexed by the spring's first node; then each
// node gathers its own springs in a fixed order (spring_runs.hpp) for the inverse diagonal blocks
// (a block Jacobi preconditioner) and b. Multiply and Precondition work on one grid row, for the
// solver's row-parallel loops. Nothing depends on the thread count.
//
// The bending (bending.hpp) is linear, f = -B Q (x + beta v): dF/dx = -B Q, dF/dv = -beta B Q,
// so it adds (h^2 + h beta) B Q to A and -h^2 B Q v to b, computed node by node from p's
// five-point stencils (no blocks stored).
//
// Pinned nodes are filtered out (Baraff and Witkin's S): their rows of A p and of b are zero and
// their preconditioner block is zero, so a solve from dv = 0 keeps their dv at exactly 0.
#pragma once

#include <vector>

#include "server/sim/cloth_model.hpp"
#include "server/sim/cloth_state.hpp"
#include "server/sim/forces.hpp"
#include "server/sim/node_vectors.hpp"

namespace flagsim::sim {

template <typename Real>
class SpringJacobian {
 public:
  /// Blocks and preconditioner at `state` for step h, and the right-hand side b from `forces`
  /// (F at the state). The model must outlive every later call.
  void Assemble(const ClothModel<Real>& model, const ClothState<Real>& state, const NodeForces<Real>& forces,
                double h, double friction, int threads, NodeVectors<Real>* rhs);

  /// Row r of A p.
  void Multiply(const NodeVectors<Real>& p, int r, NodeVectors<Real>* out) const;
  /// Row r of P^-1 residual, P the diagonal 3x3 blocks of A.
  void Precondition(const NodeVectors<Real>& residual, int r, NodeVectors<Real>* out) const;

  /// Zeroes the pinned nodes' entries: S v.
  void Filter(NodeVectors<Real>* v) const;

  int rows() const { return model_->rows; }
  int cols() const { return model_->cols; }

 private:
  /// Per spring of one family, indexed by its first node: the block iso I + axial u u^T.
  struct FamilyBlocks {
    std::vector<Real> ux, uy, uz, iso, axial, axial_stiffness;
  };
  /// A symmetric 3x3 block per node.
  struct NodeBlocks {
    std::vector<Real> xx, xy, xz, yy, yz, zz;
  };

  void Resize();
  void BlockRow(const ClothState<Real>& state, Real h, int r);
  void InverseDiagonalRow(int r);
  void RightHandSideRow(const ClothState<Real>& state, const NodeForces<Real>& forces, Real h, int r,
                        NodeVectors<Real>* rhs) const;
  /// out[a] += sum over row r's springs of (iso I + axial u u^T)(p_a - p_other), axial chosen by
  /// `axial` (the solve's or the stiffness-only coefficients).
  void AddSpringProducts(const Real* px, const Real* py, const Real* pz, int r,
                         std::vector<Real> FamilyBlocks::*axial, NodeVectors<Real>* out) const;

  /// h^2 + h beta: B Q's factor in A.
  Real BendingFactor() const { return h_ * h_ + h_ * model_->bending_damping; }
  /// out[i] += scale (B Q p)[i] over row r.
  void AddBendingProducts(const Real* px, const Real* py, const Real* pz, int r, Real scale,
                          NodeVectors<Real>* out) const;

  const ClothModel<Real>* model_ = nullptr;
  Real h_ = 0;
  std::vector<FamilyBlocks> blocks_;
  std::vector<Real> scaled_mass_;  ///< m (1 + h friction) per node
  std::vector<Real> free_;         ///< 1 per free node, 0 per pinned node: the filter S
  NodeBlocks inverse_diagonal_;    ///< zero at pinned nodes
};

}  // namespace flagsim::sim
