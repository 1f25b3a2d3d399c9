// The patch tree: regions joined from their halves hold them, and the descent reaches every
// pair of patches that the cones and boxes do not excuse, once.
#include "server/sim/collision/patch_tree.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>
#include <utility>
#include <vector>

#include "server/sim/cloth_mesh.hpp"

namespace flagsim::sim {
namespace {

constexpr int kCols = 15, kRows = 11, kCells = 2;  ///< 7 x 5 patches, the last row and column cut short
constexpr double kLanesTolerance = 1e-7;           ///< rad, as normal_cone_test.cpp

PatchTree Tree() { return PatchTree(BuildClothPatches(BuildClothMesh(kCols, kRows), kCols, kRows, kCells)); }

NormalCone ConeOf(const Point& axis, double half_angle) {
  return {axis.normalized(), std::cos(half_angle), std::sin(half_angle)};
}

/// Patch p's rectangle of cells in the plane z = 0, grown by `grow` cells.
LaneBox PlaneBox(const ClothPatch& patch, float grow) {
  const float x0 = float(patch.col * kCells) - grow, y0 = float(patch.row * kCells) - grow;
  return LaneBox::Of(x0, y0, 0, x0 + kCells + 2 * grow, y0 + kCells + 2 * grow, 0);
}

/// The patches under `region`.
std::vector<int> Leaves(const PatchTree& tree, int region) {
  const PatchRegion& r = tree.regions()[region];
  if (r.leaf()) return {r.patch};
  std::vector<int> leaves = Leaves(tree, r.left), right = Leaves(tree, r.right);
  leaves.insert(leaves.end(), right.begin(), right.end());
  return leaves;
}

/// How often the descent reached each pair of patches, lower first, and whether it found them
/// touching.
std::map<std::pair<int, int>, std::pair<int, bool>> Reached(const PatchTree& tree) {
  std::vector<PatchTree::PatchPair> pairs;
  tree.FindPatchPairs(&pairs);
  std::map<std::pair<int, int>, std::pair<int, bool>> reached;
  for (const PatchTree::PatchPair& pair : pairs) {
    auto& [count, touching] = reached[std::minmax(pair.first, pair.second)];
    ++count;
    touching = pair.touching;
  }
  return reached;
}

// Open cones excuse nothing: the descent reaches exactly the pairs whose boxes overlap, each
// once, and knows which touch (share a node: patches side by side or corner to corner).
TEST(PatchTree, WithOpenConesEveryPairWhoseBoxesOverlapIsReachedOnce) {
  for (const float grow : {0.0f, 0.25f, 1.5f}) {
    PatchTree tree = Tree();
    for (int p = 0; p < tree.patch_count(); ++p) tree.leaf_box(p) = PlaneBox(tree.patch(p), grow);
    tree.JoinUpwards();
    const auto reached = Reached(tree);
    int overlapping = 0;
    for (int p = 0; p < tree.patch_count(); ++p) {
      for (int q = p; q < tree.patch_count(); ++q) {
        const auto found = reached.find({p, q});
        if (!tree.leaf_box(p).Overlaps(tree.leaf_box(q))) {
          EXPECT_EQ(found, reached.end()) << p << ", " << q;
          continue;
        }
        ++overlapping;
        ASSERT_NE(found, reached.end()) << p << ", " << q;
        EXPECT_EQ(found->second.first, 1) << p << ", " << q;
        const ClothPatch &a = tree.patch(p), &b = tree.patch(q);
        EXPECT_EQ(found->second.second, std::abs(a.row - b.row) <= 1 && std::abs(a.col - b.col) <= 1);
      }
    }
    EXPECT_EQ(int(reached.size()), overlapping);
  }
}

// Each region above the patches holds its halves: its box is theirs together, and its cone
// holds both their cones.
TEST(PatchTree, RegionsHoldTheirHalves) {
  PatchTree tree = Tree();
  std::mt19937 random(3);
  std::uniform_real_distribution<double> tilt(-0.4, 0.4), half_angle(0.0, 0.5), place(-1, 1);
  for (int p = 0; p < tree.patch_count(); ++p) {
    tree.leaf_cone(p) = ConeOf({tilt(random), tilt(random), 1}, half_angle(random));
    const float x = float(place(random)), y = float(place(random)), z = float(place(random));
    tree.leaf_box(p) = LaneBox::Of(x, y, z, x + 0.5f, y + 0.5f, z + 0.5f);
  }
  tree.JoinUpwards();
  for (int r = 0; r < int(tree.regions().size()); ++r) {
    const PatchRegion& region = tree.regions()[r];
    if (region.leaf()) continue;
    const LaneBox both = tree.box(region.left).Joined(tree.box(region.right));
    EXPECT_TRUE((tree.box(r).lo == both.lo).all() && (tree.box(r).hi == both.hi).all()) << "region " << r;
    const NormalCone& cone = tree.cone(r);
    if (!cone.Narrow()) continue;
    for (const int half : {region.left, region.right}) {
      const NormalCone& inner = tree.cone(half);
      ASSERT_TRUE(inner.Narrow());
      const Point side = inner.axis.unitOrthogonal(), other = inner.axis.cross(side);
      for (int k = 0; k < 16; ++k) {
        const double turn = 2 * M_PI * k / 16;
        const Point rim =
            inner.cos_half * inner.axis + inner.sin_half * (std::cos(turn) * side + std::sin(turn) * other);
        EXPECT_LE(std::atan2(rim.cross(cone.axis).norm(), rim.dot(cone.axis)),
                  std::atan2(cone.sin_half, cone.cos_half) + kLanesTolerance);
      }
    }
  }
  EXPECT_TRUE(tree.cone(int(tree.regions().size()) - 1).Narrow());  // normals within 70 degrees of z
}

// A flag whose normals all keep near one direction cannot meet itself: nothing is reached. Fold
// it (one half facing +z, the other -z) and no half meets itself, but every patch of one half
// may meet every patch of the other, touching or not.
TEST(PatchTree, NarrowConesExcuseRegionsAndTheirTouchingNeighbours) {
  PatchTree tree = Tree();
  const int root = int(tree.regions().size()) - 1;
  for (int p = 0; p < tree.patch_count(); ++p) {
    tree.leaf_box(p) = LaneBox::Of(0, 0, 0, 1, 1, 1);  // every box overlaps every other
    tree.leaf_cone(p) = ConeOf(Point::UnitZ(), 0.2);
  }
  tree.JoinUpwards();
  EXPECT_TRUE(Reached(tree).empty());
  const std::vector<int> near = Leaves(tree, tree.regions()[root].left),
                         far = Leaves(tree, tree.regions()[root].right);
  for (int p : far) tree.leaf_cone(p) = ConeOf(-Point::UnitZ(), 0.2);
  tree.JoinUpwards();
  const auto reached = Reached(tree);
  EXPECT_EQ(reached.size(), near.size() * far.size());
  for (int p : near) {
    for (int q : far) EXPECT_EQ(reached.count(std::minmax(p, q)), 1u) << p << ", " << q;
  }
}

}  // namespace
}  // namespace flagsim::sim
