// The sheet's bending: a material stiffness B (N m) on the discrete curvature, the same cloth at
// every grid.
//
// Model: the quadratic bending energy of an isometrically deforming sheet (Bergou, Wardetzky,
// Harmon, Zorin and Grinspun 2006, "A quadratic bending model for inextensible surfaces"), in
// its vertex form (Wardetzky, Bergou, Harmon, Zorin and Grinspun 2007, "Discrete quadratic
// curvature energies"):
//   E = (B / 2) sum over interior nodes j of A_j |(L x)_j|^2
// with L the cotangent Laplacian of the flat rest mesh and A_j = dx dy the node's area. For an
// isometric bend, (L x)_j is the mean curvature normal (k1 + k2) n, so E tends to
// (B / 2) integral of (k1 + k2)^2 dA: a cylinder of radius R stores B / (2 R^2) per square metre
// at any grid. On this grid's right triangles the cotangent of each diagonal's opposite angle is
// cot 90 = 0, and L is the five-point Laplacian:
//   (L x)_j = (x_{j-1} - 2 x_j + x_{j+1}) / dx^2 + (x_{j-cols} - 2 x_j + x_{j+cols}) / dy^2.
// Interior nodes are those with all four neighbours; the sum leaves out the boundary's nodes,
// whose Laplacian is not a curvature, so the flat sheet (any affine map of it) has E = 0.
// (Bergou's edge form, a hinge per interior edge, is 3x stiffer against bends along this grid's
// diagonals than along its rows on these triangles: measured, docs/physics.md.)
//
// E = (1/2) x^T (B Q) x with the constant matrix Q = sum_j A s_j s_j^T, s_j the stencil of
// (L x)_j; so the force is linear, f = -B Q x, computed as two Laplacians:
//   k = D L x   (D keeps the interior nodes: the curvature, 0 on the boundary)
//   f = -B A L^T k = -B A L k   (L symmetric on the padded grid; k vanishes outside the interior)
// The Jacobian is -B Q, constant: implicit Euler adds h^2 B Q to its matrix, projective dynamics
// puts it in the global step's factorised matrix, XPBD projects each interior node's
// s_j . x = 0 with compliance 1 / (B A).
#pragma once

#include <array>
#include <vector>

#include "server/sim/cloth_model.hpp"

namespace flagsim::sim {

/// The five-point stencil's weights: (L x)_j = along (x_{j-1} + x_{j+1}) + down (x_{j-cols} +
/// x_{j+cols}) + centre x_j.
struct LaplacianWeights {
  double along = 0;   ///< 1/m^2: 1 / dx^2
  double down = 0;    ///< 1/m^2: 1 / dy^2
  double centre = 0;  ///< 1/m^2: -2 (along + down)
};
template <typename Real>
LaplacianWeights LaplacianOf(const ClothModel<Real>& model);

/// Whether node (r, c) has all four neighbours, so that its Laplacian is a curvature.
inline bool Interior(int rows, int cols, int r, int c) { return r > 0 && c > 0 && r + 1 < rows && c + 1 < cols; }

/// k_j = (L (x + beta v))_j for the interior nodes of rows [begin, end), 0 for the others (one
/// coordinate; v may be null, for x alone): the curvature, 1/m, and its damping part, beta the
/// model's bending_damping. `curvature` points at node 0's slot of an array with
/// BendingPadding(cols) slots before it and after the last node, which CurvatureRows never writes.
template <typename Real>
void CurvatureRows(const ClothModel<Real>& model, const Real* x, const Real* v, int begin, int end,
                   Real* curvature);

/// f_i = -B A (L k)_i for the nodes of rows [begin, end), k as CurvatureRows left it for every
/// row (0 in the padding): the bending force, N, one coordinate.
template <typename Real>
void BendingForceRows(const ClothModel<Real>& model, const Real* curvature, int begin, int end, Real* force);

/// Slots of padding a curvature array needs either side of its nodes.
inline int BendingPadding(int cols) { return cols + 1; }

/// (B Q p)_i for node (r, c) of one coordinate p, computed from p alone (no curvature array):
/// what a row-at-a-time matrix product needs.
template <typename Real>
Real BendingProductAt(const ClothModel<Real>& model, const Real* p, int r, int c);

/// B Q_ii: the diagonal of the bending matrix at node (r, c), N/m.
template <typename Real>
double BendingDiagonal(const ClothModel<Real>& model, int r, int c);

/// One interior node's stencil s_j: the five nodes and their weights, centre first.
struct BendingStencil {
  int nodes[5];
  double weights[5];  ///< 1/m^2
};
template <typename Real>
BendingStencil StencilOf(const ClothModel<Real>& model, int r, int c);

/// (L x)_j at interior node (r, c) of positions (x, y, z), in double: the mean curvature normal,
/// 1/m (its length is the curvature a statistic or an error estimate reads).
template <typename Real>
std::array<double, 3> CurvatureAt(const ClothModel<Real>& model, const std::vector<Real>& x,
                                  const std::vector<Real>& y, const std::vector<Real>& z, int r, int c);

/// E, the bending energy of positions (x, y, z), J: for tests and the lab.
template <typename Real>
double BendingEnergy(const ClothModel<Real>& model, const std::vector<Real>& x, const std::vector<Real>& y,
                     const std::vector<Real>& z);

}  // namespace flagsim::sim
