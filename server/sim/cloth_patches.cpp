#include "server/sim/cloth_patches.hpp"

#include <algorithm>
#include <cstdint>
#include <unordered_map>

namespace flagsim::sim {
namespace {

int64_t EdgeKey(int a, int b) { return int64_t(std::min(a, b)) << 32 | int64_t(std::max(a, b)); }

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

}  // namespace

ClothPatches BuildClothPatches(const ClothMesh& mesh, int cols, int rows, int cells) {
  const int cell_cols = cols - 1, cell_rows = rows - 1;
  const int patch_cols = (cell_cols + cells - 1) / cells, patch_rows = (cell_rows + cells - 1) / cells;
  ClothPatches result;
  result.patches.resize(size_t(patch_cols) * patch_rows);
  for (int p = 0; p < int(result.patches.size()); ++p) {
    result.patches[p].row = p / patch_cols;
    result.patches[p].col = p % patch_cols;
  }
  // Triangles 2k and 2k + 1 are cell k = r cell_cols + c (cloth_mesh.hpp).
  std::vector<int> node_owner(size_t(cols) * rows, -1), triangle_patch(mesh.triangles.size());
  for (int t = 0; t < int(mesh.triangles.size()); ++t) {
    const int cell = t / 2, r = cell / cell_cols, c = cell % cell_cols;
    const int p = (r / cells) * patch_cols + c / cells;
    ClothPatch& patch = result.patches[p];
    triangle_patch[t] = p;
    patch.triangles.push_back(t);
    for (int node : mesh.triangles[t]) {
      patch.nodes.push_back(node);
      if (node_owner[node] < 0) node_owner[node] = p;
    }
  }
  for (ClothPatch& patch : result.patches) {
    std::sort(patch.nodes.begin(), patch.nodes.end());
    patch.nodes.erase(std::unique(patch.nodes.begin(), patch.nodes.end()), patch.nodes.end());
  }
  for (int node = 0; node < int(node_owner.size()); ++node) {
    result.patches[node_owner[node]].owned_nodes.push_back(node);
  }
  // An edge belongs to the patch of the first triangle that has it: that patch holds it whole.
  std::unordered_map<int64_t, int> edge_index;
  for (int e = 0; e < int(mesh.edges.size()); ++e)
    edge_index[EdgeKey(mesh.edges[e][0], mesh.edges[e][1])] = e;
  std::vector<bool> owned(mesh.edges.size(), false);
  for (int t = 0; t < int(mesh.triangles.size()); ++t) {
    const std::array<int, 3>& v = mesh.triangles[t];
    for (int k = 0; k < 3; ++k) {
      const int e = edge_index.at(EdgeKey(v[k], v[(k + 1) % 3]));
      if (owned[e]) continue;
      owned[e] = true;
      result.patches[triangle_patch[t]].owned_edges.push_back(e);
    }
  }
  for (ClothPatch& patch : result.patches) std::sort(patch.owned_edges.begin(), patch.owned_edges.end());
  AddRegion(0, patch_rows, 0, patch_cols, patch_cols, &result.regions);
  return result;
}

}  // namespace flagsim::sim
