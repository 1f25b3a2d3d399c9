#include "server/sim/collision/cloth_patches.hpp"

#include <algorithm>
#include <cstdint>
#include <functional>
#include <numeric>
#include <utility>

namespace flagsim::sim {
namespace {

/// Appends the region of patch rows [row0, row1) and columns [col0, col1), after its halves;
/// returns its index.
int AddRegion(int row0, int row1, int col0, int col1, int patch_cols, std::vector<PatchRegion>* regions) {
  PatchRegion region{row0, row1, col0, col1};
  if (region.size() == 1) {
    region.patch = row0 * patch_cols + col0;
  } else if (row1 - row0 > col1 - col0) {
    const int middle = (row0 + row1) / 2;
    region.left = AddRegion(row0, middle, col0, col1, patch_cols, regions);
    region.right = AddRegion(middle, row1, col0, col1, patch_cols, regions);
  } else {
    const int middle = (col0 + col1) / 2;
    region.left = AddRegion(row0, row1, col0, middle, patch_cols, regions);
    region.right = AddRegion(row0, row1, middle, col1, patch_cols, regions);
  }
  regions->push_back(region);
  return int(regions->size()) - 1;
}

/// Each edge's index by its two nodes, for lookups.
class EdgeIndex {
 public:
  explicit EdgeIndex(const ClothMesh& mesh) : keys_(mesh.edges.size()) {
    for (int e = 0; e < int(mesh.edges.size()); ++e) keys_[e] = {Key(mesh.edges[e][0], mesh.edges[e][1]), e};
    std::sort(keys_.begin(), keys_.end());
  }
  int Of(int a, int b) const {
    return std::lower_bound(keys_.begin(), keys_.end(), std::make_pair(Key(a, b), -1))->second;
  }

 private:
  static int64_t Key(int a, int b) { return int64_t(std::min(a, b)) << 32 | int64_t(std::max(a, b)); }
  std::vector<std::pair<int64_t, int>> keys_;
};

/// Cells of the patch grid: patch (pr, pc) holds cell rows [pr cells, ...) up to the grid's edge.
struct PatchGrid {
  int cells, cell_cols, cell_rows, patch_cols, patch_rows;

  int Of(int cell_row, int cell_col) const { return (cell_row / cells) * patch_cols + cell_col / cells; }
  int RowEnd(int pr) const { return std::min((pr + 1) * cells, cell_rows); }
  int ColEnd(int pc) const { return std::min((pc + 1) * cells, cell_cols); }
};

/// Each node's and edge's patch: that of the first triangle that has it, which holds it whole.
struct Owners {
  std::vector<int> node, edge;
};

Owners FindOwners(const ClothMesh& mesh, int nodes, const std::function<int(int)>& triangle_patch) {
  const EdgeIndex edge_index(mesh);
  Owners owners{std::vector<int>(nodes, -1), std::vector<int>(mesh.edges.size(), -1)};
  for (int t = 0; t < int(mesh.triangles.size()); ++t) {
    const std::array<int, 3>& v = mesh.triangles[t];
    for (int k = 0; k < 3; ++k) {
      if (owners.node[v[k]] < 0) owners.node[v[k]] = triangle_patch(t);
      int& edge = owners.edge[edge_index.Of(v[k], v[(k + 1) % 3])];
      if (edge < 0) edge = triangle_patch(t);
    }
  }
  return owners;
}

}  // namespace

// Who owns what, how many of each list every patch has, then the lists: each kind for every
// patch in turn, filled in ascending order of what they list.
ClothPatches BuildClothPatches(const ClothMesh& mesh, int cols, int rows, int cells) {
  const PatchGrid grid{cells, cols - 1, rows - 1, (cols - 1 + cells - 1) / cells,
                       (rows - 1 + cells - 1) / cells};
  const int patch_count = grid.patch_cols * grid.patch_rows;
  // Triangles 2k and 2k + 1 are cell k = r cell_cols + c (cloth_mesh.hpp).
  const auto triangle_patch = [&](int t) { return grid.Of(t / 2 / grid.cell_cols, t / 2 % grid.cell_cols); };
  const Owners owners = FindOwners(mesh, cols * rows, triangle_patch);
  // Per patch, how many of each: nodes and triangles from its rectangle of cells.
  std::vector<int> node_count(patch_count), triangle_count(patch_count);
  std::vector<int> owned_node_count(patch_count, 0), owned_edge_count(patch_count, 0);
  for (int p = 0; p < patch_count; ++p) {
    const int pr = p / grid.patch_cols, pc = p % grid.patch_cols;
    const int cell_rows = grid.RowEnd(pr) - pr * cells, cell_cols = grid.ColEnd(pc) - pc * cells;
    node_count[p] = (cell_rows + 1) * (cell_cols + 1);
    triangle_count[p] = 2 * cell_rows * cell_cols;
  }
  for (int owner : owners.node) ++owned_node_count[owner];
  for (int owner : owners.edge) ++owned_edge_count[owner];
  ClothPatches result;
  const auto total = [](const std::vector<int>& counts) {
    return size_t(std::accumulate(counts.begin(), counts.end(), 0));
  };
  result.lists.resize(total(node_count) + total(triangle_count) + total(owned_node_count) +
                      total(owned_edge_count));
  // The spans: every patch's nodes, then every patch's triangles, ... `next[p]` is where patch
  // p's next entry of the kind being filled goes.
  int* cursor = result.lists.data();
  std::vector<int*> next(patch_count);
  const auto lay_out = [&](const std::vector<int>& counts, IndexSpan ClothPatch::*list) {
    for (int p = 0; p < patch_count; ++p) {
      next[p] = cursor;
      result.patches[p].*list = {cursor, cursor + counts[p]};
      cursor += counts[p];
    }
  };
  result.patches.resize(patch_count);
  lay_out(node_count, &ClothPatch::nodes);
  for (int p = 0; p < patch_count; ++p) {
    ClothPatch& patch = result.patches[p];
    patch.row = p / grid.patch_cols;
    patch.col = p % grid.patch_cols;
    for (int r = patch.row * cells; r <= grid.RowEnd(patch.row); ++r) {
      for (int c = patch.col * cells; c <= grid.ColEnd(patch.col); ++c) *next[p]++ = r * cols + c;
    }
  }
  lay_out(triangle_count, &ClothPatch::triangles);
  for (int t = 0; t < int(mesh.triangles.size()); ++t) *next[triangle_patch(t)]++ = t;
  lay_out(owned_node_count, &ClothPatch::owned_nodes);
  for (int node = 0; node < int(owners.node.size()); ++node) *next[owners.node[node]]++ = node;
  lay_out(owned_edge_count, &ClothPatch::owned_edges);
  for (int e = 0; e < int(owners.edge.size()); ++e) *next[owners.edge[e]]++ = e;
  AddRegion(0, grid.patch_rows, 0, grid.patch_cols, grid.patch_cols, &result.regions);
  return result;
}

}  // namespace flagsim::sim
