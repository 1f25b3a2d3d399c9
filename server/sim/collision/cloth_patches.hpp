// The flag's mesh cut into square patches of cells, the unit in which self-collision is
// culled. Every triangle belongs to one patch; every node and edge is owned by one patch that
// contains it, so a pair of primitives is examined from one pair of patches only. Above the
// patches, a binary tree of rectangles of patches, each split across its longer side: the
// regions whose flatness is judged at once.
#pragma once

#include <cstddef>
#include <vector>

#include "server/sim/cloth_mesh.hpp"

namespace flagsim::sim {

/// A run of indices inside ClothPatches::lists: one patch's nodes, triangles, ...
struct IndexSpan {
  const int* first = nullptr;
  const int* last = nullptr;

  const int* begin() const { return first; }
  const int* end() const { return last; }
  size_t size() const { return size_t(last - first); }
};

/// Every list ascending.
struct ClothPatch {
  int row = 0, col = 0;  ///< the patch's place in the grid of patches
  IndexSpan nodes;       ///< every node of its triangles
  IndexSpan triangles;   ///< its triangles (ClothMesh indices)
  IndexSpan owned_nodes, owned_edges;
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
  /// The patches' lists, one after another: a 256 x 192 flag has 12,288 patches of 2 x 2 cells,
  /// and a vector for each of their lists made flagd's peak 2.5 MB higher (the allocations'
  /// overhead and slack).
  /// The spans point in here, so ClothPatches moves (which keeps the storage) but never copies.
  std::vector<int> lists;

  ClothPatches() = default;
  ClothPatches(ClothPatches&&) = default;
  ClothPatches& operator=(ClothPatches&&) = default;
  ClothPatches(const ClothPatches&) = delete;
  ClothPatches& operator=(const ClothPatches&) = delete;
};

/// Patches of at most `cells` x `cells` cells over the cols x rows grid of `mesh`.
ClothPatches BuildClothPatches(const ClothMesh& mesh, int cols, int rows, int cells);

}  // namespace flagsim::sim
