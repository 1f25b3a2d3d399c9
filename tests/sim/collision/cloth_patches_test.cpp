#include "server/sim/collision/cloth_patches.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <utility>
#include <vector>

namespace flagsim::sim {
namespace {

std::vector<int> ToVector(const IndexSpan& span) { return {span.begin(), span.end()}; }

struct Grid {
  int cols, rows, cells;
};

class ClothPatchesTest : public ::testing::TestWithParam<Grid> {};

// Every triangle is in one patch, every node and edge is owned by one patch that holds it whole,
// and a patch's nodes are its triangles' corners: each list ascending.
TEST_P(ClothPatchesTest, ListsCoverTheMeshOnceAndHoldWhatTheyOwn) {
  const auto [cols, rows, cells] = GetParam();
  const ClothMesh mesh = BuildClothMesh(cols, rows);
  const ClothPatches patches = BuildClothPatches(mesh, cols, rows, cells);
  std::vector<int> triangle_seen(mesh.triangles.size(), 0), node_owned(size_t(cols) * rows, 0),
      edge_owned(mesh.edges.size(), 0);
  for (const ClothPatch& patch : patches.patches) {
    for (const IndexSpan& list : {patch.nodes, patch.triangles, patch.owned_nodes, patch.owned_edges}) {
      EXPECT_TRUE(std::is_sorted(list.begin(), list.end()));
    }
    std::set<int> corners;
    for (int t : patch.triangles) {
      ++triangle_seen[t];
      corners.insert(mesh.triangles[t].begin(), mesh.triangles[t].end());
    }
    EXPECT_EQ(ToVector(patch.nodes), std::vector<int>(corners.begin(), corners.end()));
    for (int node : patch.owned_nodes) {
      ++node_owned[node];
      EXPECT_EQ(corners.count(node), 1u) << "node " << node;
    }
    for (int e : patch.owned_edges) {
      ++edge_owned[e];
      EXPECT_EQ(corners.count(mesh.edges[e][0]) + corners.count(mesh.edges[e][1]), 2u) << "edge " << e;
    }
  }
  for (const std::vector<int>* counts : {&triangle_seen, &node_owned, &edge_owned}) {
    EXPECT_TRUE(std::all_of(counts->begin(), counts->end(), [](int n) { return n == 1; }));
  }
}

// The regions' tree: its last region is the whole grid of patches, and its leaves are the
// patches, each once.
TEST_P(ClothPatchesTest, RegionsSplitTheWholeFlagDownToEachPatch) {
  const auto [cols, rows, cells] = GetParam();
  const ClothPatches patches = BuildClothPatches(BuildClothMesh(cols, rows), cols, rows, cells);
  const int patch_rows = (rows - 1 + cells - 1) / cells, patch_cols = (cols - 1 + cells - 1) / cells;
  const PatchRegion& whole = patches.regions.back();
  EXPECT_EQ((std::vector<int>{whole.row0, whole.row1, whole.col0, whole.col1}),
            (std::vector<int>{0, patch_rows, 0, patch_cols}));
  std::vector<int> leaves;
  for (const PatchRegion& region : patches.regions) {
    if (region.leaf()) leaves.push_back(region.patch);
  }
  std::sort(leaves.begin(), leaves.end());
  std::vector<int> every(patches.patches.size());
  for (int p = 0; p < int(every.size()); ++p) every[p] = p;
  EXPECT_EQ(leaves, every);
}

// The spans point into the lists, which a move hands over whole.
TEST(ClothPatches, AMoveKeepsTheLists) {
  const ClothMesh mesh = BuildClothMesh(9, 7);
  ClothPatches built = BuildClothPatches(mesh, 9, 7, 2);
  const std::vector<int> nodes = ToVector(built.patches[5].nodes);
  const ClothPatches moved = std::move(built);
  EXPECT_EQ(ToVector(moved.patches[5].nodes), nodes);
}

INSTANTIATE_TEST_SUITE_P(Grids, ClothPatchesTest,
                         ::testing::Values(Grid{2, 2, 2}, Grid{9, 7, 2}, Grid{32, 24, 2}, Grid{10, 5, 3},
                                           Grid{5, 12, 4}));

}  // namespace
}  // namespace flagsim::sim
