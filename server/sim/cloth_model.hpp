// The fixed part of the flag: its grid, springs, masses and pinned nodes. Built once from
// SimParams; the state (cloth_state.hpp) is what a step changes.
//
// Grid: node (r, c) has index r * cols + c; row 0 is the top edge, column 0 the hoist edge on
// the pole. At rest the flag lies in the x-y plane: node (r, c) at (R + c dx, top - r dy, 0), the
// hoist edge on the surface of the pole of radius R (the pole's axis is the y axis), plus a small
// smooth out-of-plane imperfection of its free nodes (rest_imperfection.hpp); rest lengths are
// the flat grid's.
// Faces: each cell (r, c) is cut into two triangles,
//   upper (r, c) (r+1, c) (r, c+1)  and  lower (r+1, c) (r+1, c+1) (r, c+1),
// both wound so that their normal is +z at rest.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "server/sim/sim_params.hpp"

namespace flagsim::sim {

enum class SpringKind { kStructural, kShear };

/// All springs of one kind and direction on a grid: node (r, c) to node (r + dr, c + dc),
/// wherever both exist. A uniform grid gives every spring of a family the same constants, so
/// the force loops run over rows of the grid with no spring list and no pointers.
template <typename Real>
struct SpringFamily {
  SpringKind kind = SpringKind::kStructural;
  int dr = 0;            ///< row offset of the far node (>= 0)
  int dc = 0;            ///< column offset of the far node
  Real rest_length = 0;  ///< m
  Real stiffness = 0;    ///< N/m, per spring, stretched (|d| >= L)
  Real damping = 0;      ///< N s/m, per spring
  /// N/m, per spring, compressed (|d| < L): compression x stiffness (Choi and Ko 2002's
  /// stretch/compression split).
  Real compression_stiffness = 0;

  int first_col() const { return dc < 0 ? -dc : 0; }  ///< columns whose far node exists
  int end_col(int cols) const { return dc > 0 ? cols - dc : cols; }
};

template <typename Real>
struct ClothModel {
  int cols = 0;
  int rows = 0;
  Real dx = 0;                       ///< m, rest spacing along rows
  Real dy = 0;                       ///< m, rest spacing down columns
  std::array<double, 3> pole_top{};  ///< m, world frame; the pole runs from (0,0,0) to here

  /// Structural (0,1) (1,0); shear (1,1) (1,-1): the sheet in its plane.
  std::vector<SpringFamily<Real>> families;
  /// N m: the sheet's bending stiffness B, out of its plane (bending.hpp).
  Real bending_stiffness = 0;
  /// s: the bending's damping as a Rayleigh ratio beta, the force -beta B Q v (bending.hpp):
  /// the structural springs' c / k, so that every mode of the sheet is damped alike.
  Real bending_damping = 0;

  std::vector<Real> mass;          ///< kg per node: the flag's mass shared by area
  std::vector<Real> inverse_mass;  ///< 1/kg per node; 0 for nodes pinned to the pole

  /// Rest positions, m: where the flag starts and where pinned nodes stay.
  std::vector<Real> rest_x, rest_y, rest_z;

  int num_nodes() const { return cols * rows; }
  int num_cells() const { return (cols - 1) * (rows - 1); }
  int index(int r, int c) const { return r * cols + c; }
  bool pinned(int node) const { return inverse_mass[node] == Real(0); }
};

/// Builds the model of `params`: grid, spring constants, lumped masses, pinned hoist edge.
template <typename Real>
ClothModel<Real> BuildClothModel(const SimParams& params);

/// Updates the material constants only (the springs' stiffness, compression stiffness and
/// damping; the bending stiffness): what a parameter change needs when the grid and masses stay.
template <typename Real>
void SetMaterialConstants(const SimParams& params, ClothModel<Real>* model);

/// Bounds on the grid's highest angular frequencies, for choosing stable explicit steps.
/// Stiffness: Gershgorin's theorem on M^-1 K (max over nodes of the absolute row sum over m_i)
/// is safe but about twice the true value on these grids, so it is tightened to 1.25 times a
/// power-iteration estimate of the top eigenvalue at rest when that is lower. K is the springs'
/// stiffness at rest plus the bending's B Q. Damping: the same for M^-1 C, plus friction. K is
/// built from the stretched stiffnesses: compressed springs are no stiffer (compression <= 1), so
/// the bound holds in either regime, and so does C >= ratio K below for the springs' part.
struct FrequencyBound {
  double omega_squared = 0;  ///< (rad/s)^2, >= the largest eigenvalue of M^-1 K
  double damping_rate = 0;   ///< 1/s, >= the largest eigenvalue of M^-1 C
  /// Lower bounds on the damping of any mode of frequency w: C >= ratio K + friction M, so a
  /// mode's damping rate is at least ratio w^2 + friction. ratio = min over families c / k.
  double stiffness_damping_ratio = 0;  ///< s
  double friction = 0;                 ///< 1/s
};
template <typename Real>
FrequencyBound EstimateFrequencyBound(const ClothModel<Real>& model, double friction);

/// s: the smallest damping-to-stiffness ratio c / k over the spring families with stiffness
/// (FrequencyBound::stiffness_damping_ratio); 0 if no family has any.
template <typename Real>
double StiffnessDampingRatio(const ClothModel<Real>& model);

}  // namespace flagsim::sim
