// The broad phase of self-collision (self_collision.hpp): which primitive pairs of the cloth,
// a node and a triangle or two edges, may come within h of each other over a step.
//
//   (x0, x1, h) => swept boxes   each node's box over its straight path, grown by h/2
//               => normals       each triangle's at x0 and x1, and how far it can stray between
//               => regions       boxes and normal cones of the patch tree (patch_tree.hpp),
//                                leaves from their nodes and triangles, the rest from halves
//               => patch pairs   down the tree: a region whose cone is narrow cannot meet itself,
//                                two touching regions whose cones together stay narrow cannot
//                                meet each other, boxes apart cannot meet; two patches apart
//                                also need no plane across the line between their centres, nor
//                                square to either's mean normal, to part them (axis_span.hpp)
//               => candidates    in each patch pair, the primitives whose boxes overlap and
//                                that no plane across the line between them, nor square to the
//                                triangle's normal or to both edges, parts
//
// Why cones and not a spatial hash: a hash pays for every node and cell at every step; the cones
// cost a normal per triangle and let a smooth flag skip the rest. Threads share the normals
// (row by row), the leaves' bounds and each patch pair's candidates; the lists are joined in
// the pairs' order, so the candidates and their order are the same at any thread count.
#pragma once

#include <array>
#include <cmath>
#include <vector>

#include "server/sim/cloth_mesh.hpp"
#include "server/sim/collision/collision_geometry.hpp"
#include "server/sim/collision/lane_layout.hpp"
#include "server/sim/collision/patch_tree.hpp"
#include "server/sim/collision/primitive_pair.hpp"

namespace flagsim::sim {

/// Positions, one row per node: x, y, z in columns, so that each coordinate is contiguous.
using NodeRows = Eigen::Array<double, Eigen::Dynamic, 3>;
/// Triangle normals in float: x, y, z in columns.
using NormalRows = Eigen::Array<float, Eigen::Dynamic, 3>;

class CollisionCulling {
 public:
  static constexpr int kPatchCells = 2;                         ///< cells along a patch's side
  static constexpr int kNodeBlock = 1024;                       ///< nodes a thread takes at a time
  static constexpr int kSlots = 2 * kPatchCells * kPatchCells;  ///< triangles a patch has at most

  CollisionCulling(int cols, int rows);

  /// The pairs that may come within `h` over the step from `start` to `end`, but none whose
  /// four nodes all have inverse mass 0 (pinned or held), in an order that depends on the
  /// positions alone. They stay in candidates() until the next Find.
  /// `start_is_last_end`: `start` holds exactly the positions the last Find was given as `end`,
  /// so their triangle normals are taken over rather than worked out again.
  const std::vector<PrimitivePair>& Find(const NodeRows& start, const NodeRows& end,
                                         const std::vector<double>& inverse_mass, double h, int threads,
                                         bool start_is_last_end = false);

  const std::vector<PrimitivePair>& candidates() const { return candidates_; }
  /// The nodes of a pair: (node, triangle's a, b, c), or (edge's two, other edge's two).
  std::array<int, 4> Nodes(const PrimitivePair& pair) const;
  /// The pairs of patches (ClothPatches indices) the last Find examined, a patch with itself once.
  const std::vector<std::array<int, 2>>& patch_pairs() const { return patch_pairs_; }

 private:
  /// A node's straight path over the step, within the ball of `radius` about `centre`.
  struct NodePath {
    Point centre;
    double radius = 0;
  };

  void SweptBoxes();
  /// The cells' grid and the patches' over it.
  int cell_cols() const { return cols_ - 1; }
  int cell_rows() const { return int(start_->rows()) / cols_ - 1; }  ///< of the step being culled
  int patch_cols() const { return (cell_cols() + kPatchCells - 1) / kPatchCells; }
  int patch_rows() const { return (cell_rows() + kPatchCells - 1) / kPatchCells; }
  /// Where each patch's triangle normals wait for PatchCones (lane_layout.hpp).
  SlotRows slot_rows() const { return {kSlots, LaneColumns(patch_cols())}; }
  void TriangleNormals(bool start_is_last_end);
  /// Cells of a row at a time in TriangleNormals (a multiple of kPatchCells).
  static constexpr int kRun = 64;
  using RunValues = Eigen::Array<float, kRun, 1>;
  /// A run of `count` cells' lower or upper triangles: the first one's nodes, a, b and c; the
  /// rest follow a node apart.
  struct RunOfCells {
    int a, b, c, count;
  };
  /// The normals (b - a) x (c - a) of the run's triangles at positions `x`, into their slots'
  /// rows: those of the patches' cell column dc from row first(dc) on.
  template <typename SlotRow>
  void StoreNormals(const NodeRows& x, const RunOfCells& run, const SlotRow& first,
                    NormalRows* normals) const;
  static void Deal(const RunValues& values, int count, int dc, float* to);
  LaneBox TriangleBox(int triangle) const;
  LaneBox EdgeBox(int edge) const;
  /// A primitive of one patch inside another's box, and its own box.
  struct Near {
    int index;
    LaneBox box;
  };
  /// The leaf cones of patch row `pr`'s kPatchLanes patches from column `first_col` on.
  void PatchCones(int pr, int first_col);
  void RegionBounds();
  void PatchPairs();
  bool Separated(int p, int q) const;
  void Candidates();
  void AddPairs(int p, int q, std::vector<Near>* near, std::vector<PrimitivePair>* found) const;
  bool Parted(const PrimitivePair& pair) const;

  int cols_ = 0;
  ClothMesh mesh_;
  PatchTree tree_;

  // The step being culled (valid during Find).
  const NodeRows* start_ = nullptr;
  const NodeRows* end_ = nullptr;
  const std::vector<double>* inverse_mass_ = nullptr;
  double h_ = 0;
  int threads_ = 1;

  std::vector<LaneBox> node_box_;    ///< per node, its swept box grown by h/2
  std::vector<NodePath> node_path_;  ///< per node
  Eigen::VectorXd moved_by_;         ///< m, per node, |x1 - x0|
  // Per triangle, by patch: its normal (unnormalised, m^2) at the step's start and end, kept in
  // float (collision_culling.cpp says how the cones allow for it), and curl >= |du x dv|, which
  // bounds how far the normal strays between them. A patch's triangles in ClothMesh order fill
  // its slots 0 to kSlots - 1, in the rows slot_rows() gives (lane_layout.hpp).
  NormalRows normal_start_, normal_end_;
  Eigen::ArrayXf normal_curl_;
  std::vector<PatchTree::PatchPair> reached_;    ///< the pairs the tree's descent reached
  std::vector<std::array<int, 2>> patch_pairs_;  ///< patches to examine, a patch with itself or another
  std::vector<std::vector<PrimitivePair>> pair_candidates_;  ///< per patch pair, its candidates
  std::vector<std::vector<Near>>
      near_;  ///< per participant, scratch: one patch's primitives in another's box
  std::vector<PrimitivePair> candidates_;
};

}  // namespace flagsim::sim
