// The flag's surface as a triangle mesh: the faces and edges that the grid of cloth_model.hpp
// implies, listed once for the collision code (the force loops walk the grid directly).
//
// Cell (r, c) is cut along its diagonal (r+1, c)-(r, c+1) into
//   upper (r, c) (r+1, c) (r, c+1)  and  lower (r+1, c) (r+1, c+1) (r, c+1),
// triangles 2 (r (cols-1) + c) and 2 (r (cols-1) + c) + 1. Edges: every row edge, column edge
// and cell diagonal, once.
#pragma once

#include <array>
#include <vector>

namespace flagsim::sim {

struct ClothMesh {
  std::vector<std::array<int, 3>> triangles;  ///< node indices, counter-clockwise seen from +z at rest
  std::vector<std::array<int, 2>> edges;      ///< node indices, lower first

  /// True when triangle `t` has node `node` as a corner.
  bool HasCorner(int t, int node) const {
    const std::array<int, 3>& v = triangles[t];
    return v[0] == node || v[1] == node || v[2] == node;
  }
  /// True when edges `a` and `b` share a node.
  bool Adjacent(int a, int b) const {
    const std::array<int, 2>&p = edges[a], &q = edges[b];
    return p[0] == q[0] || p[0] == q[1] || p[1] == q[0] || p[1] == q[1];
  }
};

/// The mesh of a cols x rows grid (node (r, c) has index r cols + c).
ClothMesh BuildClothMesh(int cols, int rows);

}  // namespace flagsim::sim
