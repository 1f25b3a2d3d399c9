// A flag's state carried from one grid to another over the cloth's own coordinates (u, v): the
// node of a grid at column c and row r sits at u = c / (cols - 1) along the flag and
// v = r / (rows - 1) down it, whatever the grid. A node of the new grid takes the positions and
// velocities of the old grid's surface at its (u, v), bilinear in the old grid's cell there;
// the hoist's nodes stay pinned where the new model puts them. Nodes of the new grid that lie on
// nodes of the old (a grid refined by halving its spacing, and back) are copied exactly.
//
// What the server does when it changes the simulated grid (and the lab, to compare two grids
// point by point). Bilinear interpolation leaves a smooth cloth within (h^2 / 8) |curvature| of
// its surface, h the old grid's spacing; a coarser grid keeps only what its spacing can hold.
#pragma once

#include "server/sim/cloth_model.hpp"
#include "server/sim/cloth_state.hpp"

namespace flagsim::sim {

/// `state` of `from`'s grid, resampled onto `to`'s grid; time and step are kept.
template <typename Real>
ClothState<Real> Resample(const ClothModel<Real>& from, const ClothState<Real>& state,
                               const ClothModel<Real>& to);

}  // namespace flagsim::sim
