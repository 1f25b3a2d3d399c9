// The cloth drawn as a smooth surface through its nodes, so that a coarse simulated grid does not
// look faceted: the grid refined `factor` times along each side through the uniform Catmull-Rom
// surface of its nodes, as many times as the picture needs.
//
//   surface   tensor product of Catmull-Rom splines: between nodes i and i+1 of a row (or column),
//             p(t) = 1/2 [2 p_i + (p_{i+1} - p_{i-1}) t + (2 p_{i-1} - 5 p_i + 4 p_{i+1} - p_{i+2}) t^2
//                          + (3 p_i - p_{i-1} - 3 p_{i+1} + p_{i+2}) t^3],
//             past an edge a mirrored node (p_{-1} = 2 p_0 - p_1); it passes through every node
//             exactly (t = 0 weighs p_i alone) and its tangents are continuous across them
//   the pole  a refined point closer to the pole's axis than its radius is moved out to it, so
//             the cloth never shows inside the pole (a chord between two hoist nodes would)
//   factor    the nearest node's cells, projected, at most kTargetCellPixels across: 1 (the grid
//             itself) up to kMaxRefinement
#pragma once

#include <vector>

#include "server/render/camera.hpp"

namespace flagsim::render {

constexpr float kTargetCellPixels = 12;  ///< px across a drawn cell, at most, where the flag is nearest
constexpr int kMaxRefinement = 4;

/// A grid of nodes: cols x rows, node r * cols + c, positions in three arrays (m).
struct NodeGrid {
  int cols = 0, rows = 0;
  std::vector<float> x, y, z;
};

/// How many times to refine `grid` for `camera`: 1 .. kMaxRefinement.
int RefinementFor(const NodeGrid& grid, const Camera& camera);

/// `grid` refined `factor` times along each side ((cols - 1) factor + 1 columns, likewise rows)
/// through its Catmull-Rom surface, points kept at least `pole_radius` from the pole's axis (the
/// vertical line x = z = 0). factor 1 copies the grid.
void RefineGrid(const NodeGrid& grid, int factor, float pole_radius, NodeGrid* refined);

}  // namespace flagsim::render
