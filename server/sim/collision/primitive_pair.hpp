// A pair of the cloth's primitives that may meet: a node and a triangle, or two edges. The
// culling finds them (collision_culling.hpp) and self-collision acts on them
// (self_collision.hpp), both through their four nodes:
//   point-triangle  (p, a, b, c)      the node, then the triangle's corners
//   edge-edge       (p0, p1, q0, q1)  the first edge's nodes, then the other's
#pragma once

#include <array>
#include <vector>

namespace flagsim::sim {

struct PrimitivePair {
  bool edges = false;  ///< edge-edge; else point-triangle
  int a = 0, b = 0;    ///< node and triangle, or two edges (ClothMesh indices)

  /// How many of the four nodes belong to the first primitive: 1 (the point) or 2 (an edge).
  int first_nodes() const { return edges ? 2 : 1; }
};

/// Whether no node of the four can move: every one pinned to the pole or held by the fail-safe
/// (inverse mass 0, 1/kg). No impulse acts on such a pair, and the culling leaves it out.
inline bool Immobile(const std::array<int, 4>& nodes, const std::vector<double>& inverse_mass) {
  return inverse_mass[nodes[0]] == 0 && inverse_mass[nodes[1]] == 0 && inverse_mass[nodes[2]] == 0 &&
         inverse_mass[nodes[3]] == 0;
}

}  // namespace flagsim::sim
