// The flag's mesh cut into square patches of cells, the unit in which self-collision is
// culled. Every triangle belongs to one patch; every node and edge is owned by one patch that
// contains it, so a pair of primitives is examined from one pair of patches only. Above the
// patches, a binary tree of rectangles of patches, each split across its longer side: the
// regions whose flatness is judged at once.
#pragma once

#include <vector>

#include "server/sim/cloth_mesh.hpp"

namespace flagsim::sim {

struct ClothPatch {
  int row = 0, col = 0;        ///< the patch's place in the grid of patches
  std::vector<int> nodes;      ///< every node of its triangles
  std::vector<int> triangles;  ///< its triangles (ClothMesh indices)
  std::vector<int> owned_nodes, owned_edges;
};

/// A rectangle of patches, rows [row0, row1) and columns [col0, col1) of the patch grid: a
/// patch (leaf) or the union of two smaller rectangles.
struct PatchRegion {
  int row0 = 0, row1 = 0, col0 = 0, col1 = 0;
  int left = -1, right = -1;  ///< the halves (indices into ClothPatches::regions); -1 for a leaf
  int patch = -1;             ///< the leaf's patch

  bool leaf() const { return left < 0; }
  int size() const { return (row1 - row0) * (col1 - col0); }
  /// True when the two rectangles share at least a node of the mesh.
  bool Touches(const PatchRegion& other) const {
    return row0 <= other.row1 && other.row0 <= row1 && col0 <= other.col1 && other.col0 <= col1;
  }
};

struct ClothPatches {
  std::vector<ClothPatch> patches;
  /// Every region after its halves; the last is the whole flag.
  std::vector<PatchRegion> regions;
};

/// Patches of at most `cells` x `cells` cells over the cols x rows grid of `mesh`.
ClothPatches BuildClothPatches(const ClothMesh& mesh, int cols, int rows, int cells);

}  // namespace flagsim::sim
