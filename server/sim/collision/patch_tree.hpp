// The patch tree: the flag's patches under their binary tree of rectangles (cloth_patches.hpp),
// each region with the swept box and the normal cone of the step being culled, and the descent
// that finds which pairs of patches may meet. The descent is Volino and Magnenat-Thalmann's
// (1994) over a hierarchy of surface regions, with their test of regularity in the normal-cone
// form (Provot 1997; normal_cone.hpp):
//
//   SelfPairs(R)      R's cone is narrow: R cannot meet itself. Else, R a patch: the patch with
//                     itself; R larger: SelfPairs of each half, and CrossPairs of the two.
//   CrossPairs(A, B)  their boxes do not overlap: A and B cannot meet. They touch (share a node
//                     of the mesh) and their cones are narrow together: A and B are one
//                     connected surface whose normals keep under 90 degrees of one direction,
//                     which cannot meet itself. Else the larger is split and each half paired
//                     with the other, down to two patches.
//
// The culling sets the leaves' boxes and cones each step; JoinUpwards makes each larger region's
// from its halves': the box that holds both boxes, the smallest cone that holds both cones.
#pragma once

#include <vector>

#include "server/sim/collision/cloth_patches.hpp"
#include "server/sim/collision/lane_layout.hpp"
#include "server/sim/collision/normal_cone.hpp"

namespace flagsim::sim {

class PatchTree {
 public:
  explicit PatchTree(ClothPatches patches);

  const ClothPatch& patch(int p) const { return patches_.patches[p]; }
  int patch_count() const { return int(patches_.patches.size()); }
  /// Every region after its halves; the last is the whole flag (cloth_patches.hpp).
  const std::vector<PatchRegion>& regions() const { return patches_.regions; }
  const LaneBox& box(int region) const { return box_[region]; }
  const NormalCone& cone(int region) const { return cone_[region]; }

  /// Patch p's swept box and normal cone over the step, the culling's to set.
  LaneBox& leaf_box(int p) { return box_[leaf_region_[p]]; }
  NormalCone& leaf_cone(int p) { return cone_[leaf_region_[p]]; }
  const LaneBox& leaf_box(int p) const { return box_[leaf_region_[p]]; }
  const NormalCone& leaf_cone(int p) const { return cone_[leaf_region_[p]]; }

  /// Every region above the patches gets its box and cone from its halves', a level of the
  /// tree at a time, ConeLanes::kLanes regions of the level together.
  void JoinUpwards();

  /// Two patches the descent reached (`first` with itself, or two regions' patches), in the
  /// order it reached them; `touching` when they share a node of the mesh.
  struct PatchPair {
    int first = 0, second = 0;
    bool touching = false;
  };
  /// SelfPairs of the whole flag, into `pairs` (cleared first).
  void FindPatchPairs(std::vector<PatchPair>* pairs) const;

 private:
  void SelfPairs(int region, std::vector<PatchPair>* pairs) const;
  void CrossPairs(int a, int b, std::vector<PatchPair>* pairs) const;

  ClothPatches patches_;
  std::vector<int> leaf_region_;  ///< each patch's region
  /// The regions above the leaves, by height over their deepest leaf: those of height k from
  /// by_level_[level_starts_[k - 1]] on, each with its halves lower down.
  std::vector<int> by_level_, level_starts_;
  std::vector<LaneBox> box_;      ///< per region, its nodes' swept boxes together
  std::vector<NormalCone> cone_;  ///< per region, holding every normal of it over the step
};

}  // namespace flagsim::sim
