#include "server/sim/collision/patch_tree.hpp"

#include <algorithm>
#include <utility>

namespace flagsim::sim {

// Each region's height over its deepest leaf (its halves come before it), then the regions
// above the leaves by height: JoinUpwards' order.
PatchTree::PatchTree(ClothPatches patches)
    : patches_(std::move(patches)),
      leaf_region_(patches_.patches.size()),
      box_(patches_.regions.size()),
      cone_(patches_.regions.size()) {
  const std::vector<PatchRegion>& regions = patches_.regions;
  for (size_t r = 0; r < regions.size(); ++r) {
    if (regions[r].leaf()) leaf_region_[regions[r].patch] = int(r);
  }
  std::vector<int> height(regions.size(), 0);
  for (size_t r = 0; r < regions.size(); ++r) {
    if (!regions[r].leaf()) height[r] = 1 + std::max(height[regions[r].left], height[regions[r].right]);
  }
  for (int level = 1; level <= height.back(); ++level) {
    level_starts_.push_back(int(by_level_.size()));
    for (size_t r = 0; r < height.size(); ++r) {
      if (height[r] == level) by_level_.push_back(int(r));
    }
  }
  level_starts_.push_back(int(by_level_.size()));
}

// A level's regions have their halves below, so each level is joined whole before the next.
void PatchTree::JoinUpwards() {
  const std::vector<PatchRegion>& regions = patches_.regions;
  for (size_t level = 0; level + 1 < level_starts_.size(); ++level) {
    for (int first = level_starts_[level]; first < level_starts_[level + 1]; first += ConeLanes::kLanes) {
      const int count = std::min(ConeLanes::kLanes, level_starts_[level + 1] - first);
      ConeLanes left, right;
      for (int lane = 0; lane < count; ++lane) {
        const PatchRegion& region = regions[by_level_[first + lane]];
        left.Set(lane, cone_[region.left]);
        right.Set(lane, cone_[region.right]);
      }
      const ConeLanes both = ConeLanes::Union(left, right);
      for (int lane = 0; lane < count; ++lane) {
        const int r = by_level_[first + lane];
        box_[r] = box_[regions[r].left].Joined(box_[regions[r].right]);
        cone_[r] = both.Cone(lane);
      }
    }
  }
}

void PatchTree::FindPatchPairs(std::vector<PatchPair>* pairs) const {
  pairs->clear();
  SelfPairs(int(patches_.regions.size()) - 1, pairs);
}

// A region whose cone is narrow cannot meet itself; otherwise its halves are examined, each
// alone and against each other.
void PatchTree::SelfPairs(int r, std::vector<PatchPair>* pairs) const {
  const PatchRegion& region = patches_.regions[r];
  if (cone_[r].Narrow()) return;
  if (region.leaf()) {
    pairs->push_back({region.patch, region.patch, true});
    return;
  }
  SelfPairs(region.left, pairs);
  SelfPairs(region.right, pairs);
  CrossPairs(region.left, region.right, pairs);
}

// Two regions meet only if their boxes overlap, and two that touch only if their cones
// together reach 90 degrees; the larger is split until both are patches.
void PatchTree::CrossPairs(int a, int b, std::vector<PatchPair>* pairs) const {
  const PatchRegion &first = patches_.regions[a], &second = patches_.regions[b];
  if (!box_[a].Overlaps(box_[b])) return;
  const bool touching = first.Touches(second);
  if (touching && NormalCone::NarrowTogether(cone_[a], cone_[b])) return;
  if (first.leaf() && second.leaf()) {
    pairs->push_back({first.patch, second.patch, touching});
  } else if (!first.leaf() && (second.leaf() || first.size() >= second.size())) {
    CrossPairs(first.left, b, pairs);
    CrossPairs(first.right, b, pairs);
  } else {
    CrossPairs(a, second.left, pairs);
    CrossPairs(a, second.right, pairs);
  }
}

}  // namespace flagsim::sim
