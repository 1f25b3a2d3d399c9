#include "server/sim/collision/collision_culling.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "server/parallel/worker_pool.hpp"
#include "server/sim/collision/axis_span.hpp"

namespace flagsim::sim {
namespace {

// A float at most y, and one at least y (y a double or an Eigen expression of doubles): the
// bound moved outwards by kRoundingShare of itself and kRoundingLeast before it is rounded
// (lane_layout.hpp). Here, not in the header, so that the compiler inlines them into the
// vector loops.
template <typename Values>
auto FloatBelow(const Values& y) {
  return (y - (y.abs() * kRoundingShare + kRoundingLeast)).template cast<float>();
}
template <typename Values>
auto FloatAbove(const Values& y) {
  return (y + (y.abs() * kRoundingShare + kRoundingLeast)).template cast<float>();
}
float FloatBelow(double y) { return float(y - (std::abs(y) * kRoundingShare + kRoundingLeast)); }
float FloatAbove(double y) { return float(y + (std::abs(y) * kRoundingShare + kRoundingLeast)); }

}  // namespace

CollisionCulling::CollisionCulling(int cols, int rows)
    : cols_(cols),
      mesh_(BuildClothMesh(cols, rows)),
      tree_(BuildClothPatches(mesh_, cols, rows, kPatchCells)) {}

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
  PatchPairs();
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
    std::array<const double*, 3> x0, x1;
    for (int k = 0; k < 3; ++k) {
      x0[k] = start_->col(k).data() + first;
      x1[k] = end_->col(k).data() + first;
    }
    float lo[3][kNodeBlock], hi[3][kNodeBlock];
    double centre[3][kNodeBlock], moved[kNodeBlock];
#pragma omp simd
    for (int i = 0; i < count; ++i) {
      double moved_squared = 0;
      for (int k = 0; k < 3; ++k) {
        const double a = x0[k][i], b = x1[k][i];
        lo[k][i] = FloatBelow(std::min(a, b) - grow);
        hi[k][i] = FloatAbove(std::max(a, b) + grow);
        centre[k][i] = (a + b) / 2;
        moved_squared += (b - a) * (b - a);
      }
      moved[i] = std::sqrt(moved_squared);
    }
    for (int i = 0; i < count; ++i) {
      moved_by_[first + i] = moved[i];
      node_box_[first + i] = LaneBox::Of(lo[0][i], lo[1][i], lo[2][i], hi[0][i], hi[1][i], hi[2][i]);
      node_path_[first + i] = {Point(centre[0][i], centre[1][i], centre[2][i]), moved[i] / 2};
    }
  });
}

// The swept box of a triangle or an edge: its nodes' together. Made when a patch pair asks, as
// most of the flag is culled before.
LaneBox CollisionCulling::TriangleBox(int t) const {
  const auto [a, b, c] = mesh_.triangles[t];
  return node_box_[a].Joined(node_box_[b]).Joined(node_box_[c]);
}

LaneBox CollisionCulling::EdgeBox(int e) const {
  const auto [a, b] = mesh_.edges[e];
  return node_box_[a].Joined(node_box_[b]);
}

// Every triangle's normal (unnormalised), n = (b - a) x (c - a), at the step's start and end,
// and a bound on how far it strays between them: |du x dv| <= |du| |dv|, and an edge's change
// du = d_b - d_a is at most |d_a| + |d_b| for the nodes' displacements d. A run of a row's lower
// or upper triangles at a time, each coordinate a contiguous run of nodes (vectorised), then
// every kPatchCells-th into the rows of its slot. Where the step starts exactly where the last one
// ended (one pass after another, no contact between), the start normals are the last end
// normals.
void CollisionCulling::TriangleNormals(bool start_is_last_end) {
  const SlotRows rows = slot_rows();
  const int slots = rows.Count(patch_rows());
  const bool reuse = start_is_last_end && normal_end_.rows() == slots;
  if (reuse) normal_start_.swap(normal_end_);
  if (normal_curl_.rows() != slots) {  // slots that no triangle fills stay zero
    normal_start_.setZero(slots, 3);
    normal_end_.setZero(slots, 3);
    normal_curl_.setZero(slots);
  }
  ParallelFor(cell_rows(), threads_, [&](int r) {
    for (int c = 0; c < cell_cols(); c += kRun) {
      const int count = std::min(kRun, cell_cols() - c), top = r * cols_ + c, bottom = top + cols_;
      // The lower triangles (i, i + cols, i + 1) and the upper (i + cols, i + cols + 1, i + 1),
      // as cloth_mesh.hpp lists them: cell k's are triangles 2k and 2k + 1.
      for (int upper = 0; upper < 2; ++upper) {
        const RunOfCells run{upper ? bottom : top, upper ? bottom + 1 : bottom, top + 1, count};
        // Where the run's first triangle of cell column dc of its patch goes.
        const auto first = [&](int dc) {
          const int slot = ((r % kPatchCells) * kPatchCells + dc) * 2 + upper;
          return rows.Row(r / kPatchCells, slot, c / kPatchCells);
        };
        if (!reuse) StoreNormals(*start_, run, first, &normal_start_);
        StoreNormals(*end_, run, first, &normal_end_);
        const auto moved = [&](int node) { return moved_by_.array().segment(node, count); };
        RunValues curl;
        curl.head(count) = FloatAbove((moved(run.a) + moved(run.b)) * (moved(run.a) + moved(run.c)));
        for (int dc = 0; dc < kPatchCells; ++dc) Deal(curl, count, dc, normal_curl_.data() + first(dc));
      }
    }
  });
}

// Every kPatchCells-th of a run's `count` values from the dc-th on, one after another into `to`.
void CollisionCulling::Deal(const RunValues& values, int count, int dc, float* to) {
  for (int i = dc; i < count; i += kPatchCells) *to++ = values[i];
}

template <typename SlotRow>
void CollisionCulling::StoreNormals(const NodeRows& x, const RunOfCells& run, const SlotRow& first,
                                    NormalRows* normals) const {
  const double *px = x.col(0).data(), *py = x.col(1).data(), *pz = x.col(2).data();
  std::array<RunValues, 3> n;
#pragma omp simd
  for (int i = 0; i < run.count; ++i) {
    const int a = run.a + i, b = run.b + i, c = run.c + i;
    const double ux = px[b] - px[a], uy = py[b] - py[a], uz = pz[b] - pz[a];
    const double vx = px[c] - px[a], vy = py[c] - py[a], vz = pz[c] - pz[a];
    n[0][i] = float(uy * vz - uz * vy);
    n[1][i] = float(uz * vx - ux * vz);
    n[2][i] = float(ux * vy - uy * vx);
  }
  for (int dc = 0; dc < kPatchCells; ++dc) {
    for (int k = 0; k < 3; ++k) Deal(n[k], run.count, dc, normals->col(k).data() + first(dc));
  }
}

// The cones of a block of kPatchLanes patches, a patch to a lane. A patch's cone is about its mean
// normal over the step, and holds every triangle's normal n(t) = (1 - t) n0 + t n1 - t (1 - t)
// du x dv at every moment t of the step, since n(t) . d >= min(n0 . d, n1 . d) - curl / 4 and
// |n(t)| <= max(|n0|, |n1|) + curl / 4. The least of n(t) . d / |n(t)| over the triangles is
// the cone's cosine. It is worked out in float, a patch to a lane: each dot product,
// square root and quotient is off by a few 2^-24 of the ratio's scale (Higham, "Accuracy and
// Stability of Numerical Algorithms", 3.1), and so are the normals from their rounding and d
// from a unit vector; kConeRounding, subtracted from the least, is many times all of them.
void CollisionCulling::PatchCones(int pr, int first_col) {
  using Lanes = PatchLanes;
  using Vector = std::array<Lanes, 3>;
  const SlotRows rows = slot_rows();
  const auto row_of = [&](int s) { return rows.Row(pr, s, first_col); };
  const auto normal = [&](const NormalRows& normals, int s) {
    Vector n;
    for (int k = 0; k < 3; ++k) n[k] = normals.col(k).segment<kPatchLanes>(row_of(s));
    return n;
  };
  const auto dot = [](const Vector& u, const Vector& v) { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; };
  // The least each slot's ratio may be: -inf where the lane's patch has a triangle there, else
  // 1, so that an empty slot never lowers the cone.
  std::array<Lanes, kSlots> slot_floor;
  for (int lane = 0; lane < kPatchLanes; ++lane) {
    for (int s = 0; s < kSlots; ++s) {
      const int cell_row = pr * kPatchCells + s / 2 / kPatchCells;
      const int cell_col = (first_col + lane) * kPatchCells + s / 2 % kPatchCells;
      slot_floor[s][lane] = cell_row < cell_rows() && cell_col < cell_cols() ? -INFINITY : 1.0f;
    }
  }
  Vector sum{Lanes::Zero(), Lanes::Zero(), Lanes::Zero()};
  for (int s = 0; s < kSlots; ++s) {
    const Vector n0 = normal(normal_start_, s), n1 = normal(normal_end_, s);
    for (int k = 0; k < 3; ++k) sum[k] += n0[k] + n1[k];
  }
  const Lanes length = dot(sum, sum).sqrt();
  const Vector axis{sum[0] / length, sum[1] / length, sum[2] / length};
  Lanes least = Lanes::Ones();
  for (int s = 0; s < kSlots; ++s) {
    const Vector n0 = normal(normal_start_, s), n1 = normal(normal_end_, s);
    const Lanes longest = dot(n0, n0).max(dot(n1, n1)).sqrt();
    const Lanes curl = normal_curl_.segment<kPatchLanes>(row_of(s)) / 4;
    const Lanes along = dot(n0, axis).min(dot(n1, axis)) - curl;
    // At most 0 where a normal may turn 90 degrees; the least positive float keeps a degenerate
    // triangle (and an empty slot) from 0 / 0.
    const Lanes ratio = along / (longest + curl + std::numeric_limits<float>::min());
    least = least.min(ratio.max(slot_floor[s]));
  }
  for (int lane = 0; lane < kPatchLanes && first_col + lane < patch_cols(); ++lane) {
    const int p = pr * patch_cols() + first_col + lane;
    NormalCone& cone = tree_.leaf_cone(p);
    if (length[lane] == 0) {
      cone = {Point::UnitZ()};
      continue;
    }
    cone = {Point(sum[0][lane], sum[1][lane], sum[2][lane]).normalized()};
    const double cos_half = double(least[lane]) - kConeRounding;
    if (cos_half > 0) {
      cone.cos_half = cos_half;
      cone.sin_half = std::sqrt((1 - cos_half) * (1 + cos_half));
    }
  }
}

// Regions' boxes and cones: the leaves from their nodes and triangles (in parallel, a block of
// patches at a time), then the rest from their halves (PatchTree::JoinUpwards).
void CollisionCulling::RegionBounds() {
  const int blocks_in_row = slot_rows().lane_cols / kPatchLanes;
  ParallelFor(patch_rows() * blocks_in_row, threads_, [&](int block) {
    const int pr = block / blocks_in_row, first_col = block % blocks_in_row * kPatchLanes;
    PatchCones(pr, first_col);
    const int row_start = pr * patch_cols();
    for (int p = row_start + first_col; p < row_start + std::min(patch_cols(), first_col + kPatchLanes);
         ++p) {
      LaneBox box = LaneBox::Empty();
      for (int node : tree_.patch(p).nodes) box = box.Joined(node_box_[node]);
      tree_.leaf_box(p) = box;
    }
  });
  tree_.JoinUpwards();
}

// The pairs of patches the tree's descent reaches (PatchTree::FindPatchPairs), less the pairs
// of patches apart that a plane parts (Separated), in the order the descent reached them; each
// pair lower patch first.
void CollisionCulling::PatchPairs() {
  tree_.FindPatchPairs(&reached_);
  patch_pairs_.clear();
  for (const PatchTree::PatchPair& pair : reached_) {
    if (!pair.touching && Separated(pair.first, pair.second)) continue;
    patch_pairs_.push_back({std::min(pair.first, pair.second), std::max(pair.first, pair.second)});
  }
}

// Whether a plane parts the patches' nodes' paths (each within its ball, as in Parted) with
// room for h: one across the line between their centres (boxes are loose for a tilted sheet,
// and two patches of one smooth sheet a cell apart are parted along that line by about the
// cell), else one square to either patch's mean normal (two layers of a fold, one above the
// other, are parted across it).
bool CollisionCulling::Separated(int p, int q) const {
  const ClothPatch &a = tree_.patch(p), &b = tree_.patch(q);
  const auto centre = [&](const ClothPatch& patch) {
    Point sum = Point::Zero();
    for (int node : patch.nodes) sum += node_path_[node].centre;
    return Point(sum / double(patch.nodes.size()));
  };
  // What the patch's nodes' paths cover along the axis, each within its ball.
  const auto span = [&](const ClothPatch& patch, const Point& axis) {
    const double length = axis.norm();
    AxisSpan covered;
    for (int node : patch.nodes)
      covered.Add(axis.dot(node_path_[node].centre), node_path_[node].radius * length);
    return covered;
  };
  const Point between = centre(b) - centre(a);
  if (span(b, between).Beyond(span(a, between), h_ * between.norm())) return true;
  for (int patch : {p, q}) {
    const Point& normal = tree_.leaf_cone(patch).axis;
    if (Apart(span(a, normal), span(b, normal), h_ * normal.norm())) return true;
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
// itself, each edge pair once; for two patches, called both ways, the edges once). Only p's
// primitives inside q's box take part (`near` is scratch for them), and only q's whose box
// meets theirs together.
void CollisionCulling::AddPairs(int p, int q, std::vector<Near>* near,
                                std::vector<PrimitivePair>* found) const {
  const ClothPatch &from = tree_.patch(p), &to = tree_.patch(q);
  const LaneBox& to_box = tree_.leaf_box(q);
  LaneBox near_box = LaneBox::Empty();  // the near primitives' boxes together: none outside it meets one
  const auto keep_if_near = [&](int index, const LaneBox& box) {
    if (!box.Overlaps(to_box)) return;
    near->push_back({index, box});
    near_box = near_box.Joined(box);
  };
  near->clear();
  for (int node : from.owned_nodes) keep_if_near(node, node_box_[node]);
  for (int t : near->empty() ? IndexSpan{} : to.triangles) {
    const LaneBox box = TriangleBox(t);
    if (!box.Overlaps(near_box)) continue;
    for (const Near& node : *near) {
      if (!node.box.Overlaps(box) || mesh_.HasCorner(t, node.index)) continue;
      const PrimitivePair pair{false, node.index, t};
      if (!Parted(pair) && !Immobile(Nodes(pair), *inverse_mass_)) found->push_back(pair);
    }
  }
  if (p > q) return;
  near->clear();
  near_box = LaneBox::Empty();
  for (int e : from.owned_edges) keep_if_near(e, EdgeBox(e));
  for (int f : near->empty() ? IndexSpan{} : to.owned_edges) {
    const LaneBox box = EdgeBox(f);
    if (!box.Overlaps(near_box)) continue;
    for (const Near& edge : *near) {
      const int e = edge.index;
      if ((p == q && f <= e) || !edge.box.Overlaps(box) || mesh_.Adjacent(e, f)) continue;
      const PrimitivePair pair{true, std::min(e, f), std::max(e, f)};
      if (!Parted(pair) && !Immobile(Nodes(pair), *inverse_mass_)) found->push_back(pair);
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
  const int split = pair.first_nodes();
  std::array<const NodePath*, 4> path;
  for (int i = 0; i < 4; ++i) path[i] = &node_path_[n[i]];
  const auto centre = [&path](int from, int to) {
    Point sum = Point::Zero();
    for (int i = from; i < to; ++i) sum += path[i]->centre;
    return Point(sum / double(to - from));
  };
  // Whether the second primitive lies beyond the first along `axis` by more than h: one side
  // only, so an axis that points from the first towards the second can part them and its
  // opposite cannot. Unnormalised: the spans and the room are all scaled by |axis|.
  const auto parted_along = [&](const Point& axis) {
    const double length = axis.norm();
    AxisSpan first, rest;
    for (int i = 0; i < split; ++i) first.Add(axis.dot(path[i]->centre), path[i]->radius * length);
    for (int i = split; i < 4; ++i) rest.Add(axis.dot(path[i]->centre), path[i]->radius * length);
    return rest.Beyond(first, h_ * length);
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
