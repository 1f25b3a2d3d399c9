#include "server/sim/collision_culling.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "server/parallel/worker_pool.hpp"

namespace flagsim::sim {
namespace {

/// Elements 0, 2, 4, ... of the run of 2 count - 1 values at `data`.
template <typename Scalar>
Eigen::Map<Eigen::Array<Scalar, Eigen::Dynamic, 1>, 0, Eigen::InnerStride<2>> EveryOther(Scalar* data,
                                                                                         int count) {
  return {data, count};
}

/// A normal worked out in double and kept in float is off by at most 2^-24 of its length
/// (rounding to nearest, each component); the cones allow twice that.
constexpr double kNormalRounding = 0x1p-23;

// Rounding to nearest puts float(y) within |y| 2^-24 of y (and within 2^-150 below 2^-126),
// so lowering a bound by 2^-22 of itself and a little more before rounding keeps it below;
// raising it likewise keeps it above. Under a micrometre at the flag's few metres.
constexpr double kRoundingShare = 0x1p-22, kRoundingLeast = 1e-30;
template <typename Values>
auto FloatBelow(const Values& y) {
  return (y - (y.abs() * kRoundingShare + kRoundingLeast)).template cast<float>();
}
template <typename Values>
auto FloatAbove(const Values& y) {
  return (y + (y.abs() * kRoundingShare + kRoundingLeast)).template cast<float>();
}

}  // namespace

CollisionCulling::CollisionCulling(int cols, int rows)
    : cols_(cols),
      mesh_(BuildClothMesh(cols, rows)),
      patches_(BuildClothPatches(mesh_, cols, rows, kPatchCells)) {
  leaf_region_.resize(patches_.patches.size());
  for (size_t r = 0; r < patches_.regions.size(); ++r) {
    if (patches_.regions[r].leaf()) leaf_region_[patches_.regions[r].patch] = int(r);
  }
}

const std::vector<PrimitivePair>& CollisionCulling::Find(const NodeRows& start, const NodeRows& end,
                                                         const std::vector<double>& inverse_mass, double h,
                                                         int threads, bool start_is_last_end) {
  start_ = &start;
  end_ = &end;
  inverse_mass_ = &inverse_mass;
  h_ = h;
  threads_ = threads;
  SweptBoxes();
  TriangleNormals(start_is_last_end);
  RegionBounds();
  patch_pairs_.clear();
  SelfPairs(int(patches_.regions.size()) - 1);
  Candidates();
  return candidates_;
}

// Each node's box, grown by h/2 so that two boxes overlap when within h, how far it moved,
// |x1 - x0|, and the ball about its path: centre (x0 + x1) / 2, radius |x1 - x0| / 2. A block
// of nodes at a time, each coordinate as a contiguous run (vectorised), then node by node into
// the boxes and balls.
void CollisionCulling::SweptBoxes() {
  const int nodes = int(start_->rows());
  const double grow = h_ / 2;
  node_box_.resize(nodes);
  node_path_.resize(nodes);
  moved_by_.resize(nodes);
  ParallelFor((nodes + kNodeBlock - 1) / kNodeBlock, threads_, [&](int block) {
    const int first = block * kNodeBlock, count = std::min(nodes - first, kNodeBlock);
    const auto x0 = start_->middleRows(first, count), x1 = end_->middleRows(first, count);
    const auto d = x1 - x0;
    moved_by_.segment(first, count) = (d.col(0).square() + d.col(1).square() + d.col(2).square()).sqrt();
    Eigen::Array<float, kNodeBlock, 3> lo, hi;
    Eigen::Array<double, kNodeBlock, 3> centre;
    for (int k = 0; k < 3; ++k) {
      lo.col(k).head(count) = FloatBelow(x0.col(k).min(x1.col(k)) - grow);
      hi.col(k).head(count) = FloatAbove(x0.col(k).max(x1.col(k)) + grow);
      centre.col(k).head(count) = (x0.col(k) + x1.col(k)) / 2;
    }
    for (int i = 0; i < count; ++i) {
      node_box_[first + i] = {{lo(i, 0), lo(i, 1), lo(i, 2), 0.0f}, {hi(i, 0), hi(i, 1), hi(i, 2), 0.0f}};
      node_path_[first + i] = {centre.row(i).transpose().matrix(), moved_by_[first + i] / 2};
    }
  });
}

// The swept box of a triangle or an edge: its nodes' together. Made when a patch pair asks, as
// most of the flag is culled before.
CollisionCulling::Box CollisionCulling::TriangleBox(int t) const {
  const auto [a, b, c] = mesh_.triangles[t];
  return node_box_[a].Joined(node_box_[b]).Joined(node_box_[c]);
}

CollisionCulling::Box CollisionCulling::EdgeBox(int e) const {
  const auto [a, b] = mesh_.edges[e];
  return node_box_[a].Joined(node_box_[b]);
}

// Every triangle's normal (unnormalised) at the step's start and end, the longer, and a bound
// on how far the normal strays between them: |du x dv| <= |du| |dv|, and an edge's change
// du = d_b - d_a is at most |d_a| + |d_b| for the nodes' displacements d. Row by row of cells,
// each coordinate of a row a contiguous run: the arithmetic is vectorised. Where the step starts
// exactly where the last one ended (one pass after another, no contact between), the start
// normals are the last end normals.
void CollisionCulling::TriangleNormals(bool start_is_last_end) {
  const int cells = cols_ - 1, rows = int(start_->rows()) / cols_, triangles = 2 * cells * (rows - 1);
  const bool reuse = start_is_last_end && normal_end_.rows() == triangles;
  if (reuse) normal_start_.swap(normal_end_);
  normal_start_.resize(triangles, 3);
  normal_end_.resize(triangles, 3);
  normal_curl_.resize(triangles);
  const auto moved = [&](int node) { return moved_by_.array().segment(node, cells); };
  ParallelFor(rows - 1, threads_, [&](int r) {
    const int top = r * cols_, bottom = top + cols_, first = 2 * r * cells;
    if (!reuse) CellNormals(*start_, top, bottom, cells, first, &normal_start_);
    CellNormals(*end_, top, bottom, cells, first, &normal_end_);
    EveryOther(normal_curl_.data() + first, cells) =
        (moved(top) + moved(bottom)) * (moved(top) + moved(top + 1));
    EveryOther(normal_curl_.data() + first + 1, cells) =
        (moved(bottom) + moved(bottom + 1)) * (moved(bottom) + moved(top + 1));
  });
  const auto squared = [](const NormalRows& n) {
    return n.col(0).cast<double>().square() + n.col(1).cast<double>().square() +
           n.col(2).cast<double>().square();
  };
  normal_longest_ = squared(normal_start_).max(squared(normal_end_)).sqrt();
}

// The normals (b - a) x (c - a) of a row of cells' two triangles, as cloth_mesh.hpp lists them:
// (i, i + cols, i + 1) into rows first, first + 2, ... of `normals` and
// (i + cols, i + cols + 1, i + 1) into first + 1, first + 3, ..., for i from `top` on and
// i + cols from `bottom` on.
void CollisionCulling::CellNormals(const NodeRows& x, int top, int bottom, int cells, int first,
                                   NormalRows* normals) {
  const auto run = [&x, cells](int k, int node) { return x.col(k).segment(node, cells); };
  for (int upper = 0; upper < 2; ++upper) {
    const int a = upper ? bottom : top, b = upper ? bottom + 1 : bottom, c = top + 1;
    const auto u = [&](int k) { return run(k, b) - run(k, a); };
    const auto v = [&](int k) { return run(k, c) - run(k, a); };
    for (int k = 0; k < 3; ++k) {
      const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
      EveryOther(normals->col(k).data() + first + upper, cells) =
          (u(k1) * v(k2) - u(k2) * v(k1)).template cast<float>();
    }
  }
}

// The cone of a leaf patch: about its mean normal over the step, holding every triangle's
// normal n(t) = (1 - t) n0 + t n1 - t (1 - t) du x dv at every moment t of the step, since
// n(t) . d >= min(n0 . d, n1 . d) - curl / 4 and |n(t)| <= max(|n0|, |n1|) + curl / 4. The
// least of n(t) . d / |n(t)| over the triangles is the cone's cosine. With n0 and n1 kept in
// float, each bound gives up their rounding too (kNormalRounding of the longer).
NormalCone CollisionCulling::PatchCone(const ClothPatch& patch) const {
  Point sum = Point::Zero();
  const auto normal = [](const NormalRows& rows, int t) {
    return Point(rows.row(t).transpose().cast<double>().matrix());
  };
  for (int t : patch.triangles) sum += normal(normal_start_, t) + normal(normal_end_, t);
  const double length = sum.norm();
  if (length == 0) return {Point::UnitZ()};
  const Point axis = sum / length;
  double least = 1;
  for (int t : patch.triangles) {
    const double curl = normal_curl_[t] / 4 + kNormalRounding * normal_longest_[t];
    const double along =
        std::min(normal(normal_start_, t).dot(axis), normal(normal_end_, t).dot(axis)) - curl;
    least = std::min(least, along <= 0 ? -1.0 : along / (normal_longest_[t] + curl));
  }
  if (least <= 0) return {axis};
  return {axis, least, std::sqrt((1 - least) * (1 + least))};
}

// Regions' boxes and cones: the leaves from their nodes and triangles (in parallel), then the
// rest from their halves, which come before them.
void CollisionCulling::RegionBounds() {
  const std::vector<PatchRegion>& regions = patches_.regions;
  region_box_.resize(regions.size());
  region_cone_.resize(regions.size());
  ParallelFor(int(leaf_region_.size()), threads_, [&](int p) {
    const ClothPatch& patch = patches_.patches[p];
    Box box = Box::Empty();
    for (int node : patch.nodes) box = box.Joined(node_box_[node]);
    region_box_[leaf_region_[p]] = box;
    region_cone_[leaf_region_[p]] = PatchCone(patch);
  });
  for (size_t r = 0; r < regions.size(); ++r) {
    const PatchRegion& region = regions[r];
    if (region.leaf()) continue;
    region_box_[r] = region_box_[region.left].Joined(region_box_[region.right]);
    region_cone_[r] = NormalCone::Union(region_cone_[region.left], region_cone_[region.right]);
  }
}

// A region whose cone is under 90 degrees cannot meet itself; otherwise its halves are
// examined, each alone and against each other.
void CollisionCulling::SelfPairs(int r) {
  const PatchRegion& region = patches_.regions[r];
  if (region_cone_[r].Narrow()) return;
  if (region.leaf()) {
    patch_pairs_.push_back({region.patch, region.patch});
    return;
  }
  SelfPairs(region.left);
  SelfPairs(region.right);
  CrossPairs(region.left, region.right);
}

// Two regions meet only if their boxes overlap, and two that touch only if their cones
// together reach 90 degrees; the larger is split until both are patches.
void CollisionCulling::CrossPairs(int a, int b) {
  const PatchRegion &first = patches_.regions[a], &second = patches_.regions[b];
  if (!region_box_[a].Overlaps(region_box_[b])) return;
  if (first.Touches(second) && NormalCone::NarrowTogether(region_cone_[a], region_cone_[b])) return;
  if (first.leaf() && second.leaf()) {
    if (!first.Touches(second) && Separated(first.patch, second.patch)) return;
    patch_pairs_.push_back({std::min(first.patch, second.patch), std::max(first.patch, second.patch)});
  } else if (!first.leaf() && (second.leaf() || first.size() >= second.size())) {
    CrossPairs(first.left, b);
    CrossPairs(first.right, b);
  } else {
    CrossPairs(a, second.left);
    CrossPairs(a, second.right);
  }
}

// Whether a plane parts the patches' nodes' paths (each within its ball, as in Parted) with
// room for h: one across the line between their centres (boxes are loose for a tilted sheet,
// and two patches of one smooth sheet a cell apart are parted along that line by about the
// cell), else one square to either patch's mean normal (two layers of a fold, one above the
// other, are parted across it).
bool CollisionCulling::Separated(int p, int q) const {
  const ClothPatch &a = patches_.patches[p], &b = patches_.patches[q];
  const auto centre = [&](const ClothPatch& patch) {
    Point sum = Point::Zero();
    for (int node : patch.nodes) sum += node_path_[node].centre;
    return Point(sum / double(patch.nodes.size()));
  };
  // The least and the most of axis . x over the patch's nodes' paths, each within its ball.
  const auto span = [&](const ClothPatch& patch, const Point& axis) {
    const double length = axis.norm();
    std::pair<double, double> least_most{INFINITY, -INFINITY};
    for (int node : patch.nodes) {
      const double middle = axis.dot(node_path_[node].centre), reach = node_path_[node].radius * length;
      least_most = {std::min(least_most.first, middle - reach), std::max(least_most.second, middle + reach)};
    }
    return least_most;
  };
  const Point between = centre(b) - centre(a);
  if (span(b, between).first - span(a, between).second > h_ * between.norm()) return true;
  for (int patch : {p, q}) {
    const Point& normal = region_cone_[leaf_region_[patch]].axis;
    const auto [a_least, a_most] = span(a, normal);
    const auto [b_least, b_most] = span(b, normal);
    const double room = h_ * normal.norm();
    if (b_least - a_most > room || a_least - b_most > room) return true;
  }
  return false;
}

// The boxes of every patch a pair names; then each pair's candidates into a list of its own (in
// parallel), the lists joined in the pairs' order: the same candidates in the same order at any
// thread count.
void CollisionCulling::Candidates() {
  const int count = int(patch_pairs_.size());
  if (int(pair_candidates_.size()) < count) pair_candidates_.resize(count);
  near_.resize(threads_);
  ParallelForEachParticipant(count, threads_, [&](int i, int participant) {
    const auto [p, q] = patch_pairs_[i];
    std::vector<PrimitivePair>& found = pair_candidates_[i];
    found.clear();
    AddPairs(p, q, &near_[participant], &found);
    if (p != q) AddPairs(q, p, &near_[participant], &found);
  });
  candidates_.clear();
  for (int i = 0; i < count; ++i) {
    candidates_.insert(candidates_.end(), pair_candidates_[i].begin(), pair_candidates_[i].end());
  }
}

// p's own nodes against q's triangles; p's own edges against q's own edges (for a patch with
// itself, each edge pair once; for two patches, called both ways, the edges once). Only the
// primitives inside the other patch's box take part (`near` is scratch for them).
void CollisionCulling::AddPairs(int p, int q, std::vector<Near>* near,
                                std::vector<PrimitivePair>* found) const {
  const ClothPatch &from = patches_.patches[p], &to = patches_.patches[q];
  const Box &from_box = region_box_[leaf_region_[p]], &to_box = region_box_[leaf_region_[q]];
  near->clear();
  for (int node : from.owned_nodes) {
    if (node_box_[node].Overlaps(to_box)) near->push_back({node, node_box_[node]});
  }
  for (int t : to.triangles) {
    const Box box = TriangleBox(t);
    if (!box.Overlaps(from_box)) continue;
    for (const Near& node : *near) {
      if (mesh_.HasCorner(t, node.index) || !node.box.Overlaps(box)) continue;
      const PrimitivePair pair{false, node.index, t};
      if (!Immobile(pair) && !Parted(pair)) found->push_back(pair);
    }
  }
  if (p > q) return;
  near->clear();
  for (int e : from.owned_edges) {
    const Box box = EdgeBox(e);
    if (box.Overlaps(to_box)) near->push_back({e, box});
  }
  for (int f : to.owned_edges) {
    const Box box = EdgeBox(f);
    if (!box.Overlaps(from_box)) continue;
    for (const Near& edge : *near) {
      const int e = edge.index;
      if ((p == q && f <= e) || mesh_.Adjacent(e, f) || !edge.box.Overlaps(box)) continue;
      const PrimitivePair pair{true, std::min(e, f), std::max(e, f)};
      if (!Immobile(pair) && !Parted(pair)) found->push_back(pair);
    }
  }
}

std::array<int, 4> CollisionCulling::Nodes(const PrimitivePair& pair) const {
  if (pair.edges) {
    return {mesh_.edges[pair.a][0], mesh_.edges[pair.a][1], mesh_.edges[pair.b][0], mesh_.edges[pair.b][1]};
  }
  const auto [a, b, c] = mesh_.triangles[pair.b];
  return {pair.a, a, b, c};
}

bool CollisionCulling::Immobile(const PrimitivePair& pair) const {
  const std::array<int, 4> n = Nodes(pair);
  const std::vector<double>& inverse_mass = *inverse_mass_;
  return inverse_mass[n[0]] == 0 && inverse_mass[n[1]] == 0 && inverse_mass[n[2]] == 0 &&
         inverse_mass[n[3]] == 0;
}

// Whether a plane parts the pair's two primitives with room for h over the whole step. Along
// a unit axis a, a node stays within a . c +- r of its path's ball (c, r), and a primitive
// within what its nodes' span; a gap over h between the two spans keeps them h apart at every
// moment: no proximity and no contact to find. Boxes are loose for a tilted sheet, and
// neighbours on one smooth sheet are parted this way by about half a cell. The axes, at
// mid-step: the line between the primitives' centres; for a node and a triangle, then the
// triangle's normal (a node over another layer of a fold, a little to the side); for two edges,
// that line made square to the first edge (two parallel diagonals of neighbouring cells are
// parted across it, not along it), then the direction square to both edges.
bool CollisionCulling::Parted(const PrimitivePair& pair) const {
  const std::array<int, 4> n = Nodes(pair);
  const int split = pair.edges ? 2 : 1;
  std::array<const NodePath*, 4> path;
  for (int i = 0; i < 4; ++i) path[i] = &node_path_[n[i]];
  const auto centre = [&path](int from, int to) {
    Point sum = Point::Zero();
    for (int i = from; i < to; ++i) sum += path[i]->centre;
    return Point(sum / double(to - from));
  };
  // Unnormalised: the spans and the room are all scaled by |axis|.
  const auto parted_along = [&](const Point& axis) {
    const double length = axis.norm();
    double first_most = -INFINITY, rest_least = INFINITY;
    for (int i = 0; i < split; ++i)
      first_most = std::max(first_most, axis.dot(path[i]->centre) + path[i]->radius * length);
    for (int i = split; i < 4; ++i)
      rest_least = std::min(rest_least, axis.dot(path[i]->centre) - path[i]->radius * length);
    return rest_least - first_most > h_ * length;
  };
  const Point between = centre(split, 4) - centre(0, split);
  if (parted_along(between)) return true;
  const auto c = [&path](int i) -> const Point& { return path[i]->centre; };
  // The triangle's normal.
  if (!pair.edges) return parted_along((c(2) - c(1)).cross(c(3) - c(1)));
  // The first edge at mid-step.
  const Point along = c(1) - c(0);
  const double length_squared = along.squaredNorm();
  if (length_squared > 0 && parted_along(between - along * (between.dot(along) / length_squared)))
    return true;
  return parted_along(along.cross(c(3) - c(2)));  // square to both edges
}

}  // namespace flagsim::sim
