#include "self_collision.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace flagsim::sim {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// The weights k of a pair's closest points (the pair's impulse weights, self_collision.hpp):
/// point-triangle (p, a, b, c): 1, -w_a, -w_b, -w_c; edge-edge (p0, p1, q0, q1): 1 - s, s,
/// -(1 - t), -t.
std::array<double, 4> ClosestWeights(bool edges, const std::array<Point, 4>& p) {
  if (edges) {
    const SegmentParameters c = ClosestOnSegments(p[0], p[1], p[2], p[3]);
    return {1 - c.s, c.s, -(1 - c.t), -c.t};
  }
  const Eigen::Vector3d w = ClosestOnTriangle(p[0], p[1], p[2], p[3]);
  return {1, -w[0], -w[1], -w[2]};
}

/// sum k_i p_i: from the second primitive's closest point to the first's.
Point Gap(const std::array<double, 4>& k, const std::array<Point, 4>& p) {
  return k[0] * p[0] + k[1] * p[1] + k[2] * p[2] + k[3] * p[3];
}

}  // namespace

template <typename Real>
SelfCollision<Real>::SelfCollision(const ClothModel<Real>& model)
    : cols_(model.cols),
      mesh_(BuildClothMesh(model.cols, model.rows)),
      patches_(BuildClothPatches(mesh_, model.cols, model.rows, kPatchCells)) {
  leaf_region_.resize(patches_.patches.size());
  for (size_t r = 0; r < patches_.regions.size(); ++r) {
    if (patches_.regions[r].leaf()) leaf_region_[patches_.regions[r].patch] = int(r);
  }
}

template <typename Real>
bool SelfCollision<Real>::Resolve(const ClothModel<Real>& model, const SimParams& params, double dt,
                                  const ClothState<Real>& start, ClothState<Real>* state) {
  stats_ = {};
  thickness_ = std::min(params.thickness, kSpacingShare * std::min(double(model.dx), double(model.dy)));
  dt_ = dt;
  obstacles_ = Obstacles::Of(params);
  Load(model, start, *state);
  for (int round = 0;; ++round) {
    SweptBoxes();
    TriangleNormals();
    RegionBounds();
    patch_pairs_.clear();
    SelfPairs(int(patches_.regions.size()) - 1, &patch_pairs_);
    Candidates(patch_pairs_);
    if (round == 0) {
      stats_.patch_pairs = int(patch_pairs_.size());
      stats_.candidates = int(candidates_.size());
      if (candidates_.empty()) return false;
      Proximity();
    }
    const bool hold = round >= kImpulseRounds;
    const int held_before = stats_.held;
    const int contacts = Contacts(hold);
    const bool outside = HoldThoseInObstacles();
    stats_.rounds = round + 1;
    if (contacts == 0 && outside) break;
    if (hold && stats_.held == held_before) break;  // what is left involves held nodes only
  }
  bool changed = false;
  for (int i = 0; i < state->num_nodes(); ++i) {
    if (!Moved(i)) continue;
    const Point end = End(i), dv = (end - Integrated(i)) / dt;
    state->x[i] = Real(end.x());
    state->y[i] = Real(end.y());
    state->z[i] = Real(end.z());
    state->vx[i] = Real(state->vx[i] + dv.x());
    state->vy[i] = Real(state->vy[i] + dv.y());
    state->vz[i] = Real(state->vz[i] + dv.z());
    ++stats_.moved;
    changed = true;
  }
  return changed;
}

template <typename Real>
void SelfCollision<Real>::Load(const ClothModel<Real>& model, const ClothState<Real>& start,
                               const ClothState<Real>& end) {
  const int n = model.num_nodes();
  start_.resize(n, 3);
  end_.resize(n, 3);
  inverse_mass_.resize(n);
  for (int i = 0; i < n; ++i) {
    start_.row(i) << double(start.x[i]), double(start.y[i]), double(start.z[i]);
    end_.row(i) << double(end.x[i]), double(end.y[i]), double(end.z[i]);
    inverse_mass_[i] = double(model.inverse_mass[i]);
  }
  integrated_ = end_;
}

template <typename Real>
void SelfCollision<Real>::SweptBoxes() {
  const Point grow = Point::Constant(thickness_ / 2);  // two boxes overlap when within h
  node_box_.resize(start_.rows());
  for (int i = 0; i < int(start_.rows()); ++i) {
    node_box_[i] = {Start(i).cwiseMin(End(i)) - grow, Start(i).cwiseMax(End(i)) + grow};
  }
  triangle_box_.resize(mesh_.triangles.size());
  for (size_t t = 0; t < mesh_.triangles.size(); ++t) {
    const auto [a, b, c] = mesh_.triangles[t];
    triangle_box_[t] = node_box_[a].Joined(node_box_[b]).Joined(node_box_[c]);
  }
  edge_box_.resize(mesh_.edges.size());
  for (size_t e = 0; e < mesh_.edges.size(); ++e) {
    const auto [a, b] = mesh_.edges[e];
    edge_box_[e] = node_box_[a].Joined(node_box_[b]);
  }
}

// Every triangle's normal (unnormalised) at the step's start and end, their lengths, and a
// bound on how far the normal strays between them: |du x dv| <= |du| |dv|, and an edge's
// change du = d_b - d_a is at most |d_a| + |d_b| for the nodes' displacements d.
template <typename Real>
void SelfCollision<Real>::TriangleNormals() {
  const int nodes = int(start_.rows()), cols = cols_, cell_cols = cols_ - 1, rows = nodes / cols_;
  moved_by_ = (end_ - start_).matrix().rowwise().norm();
  normals_.resize(mesh_.triangles.size());
  const auto normal = [](const Positions& x, int a, int b, int c) {
    return Point((x.row(b) - x.row(a)).matrix().cross((x.row(c) - x.row(a)).matrix()));
  };
  const auto fill = [&](int t, int a, int b, int c) {
    TriangleNormal& n = normals_[t];
    n.start = normal(start_, a, b, c);
    n.end = normal(end_, a, b, c);
    n.longest = std::sqrt(std::max(n.start.squaredNorm(), n.end.squaredNorm()));
    n.curl = (moved_by_[a] + moved_by_[b]) * (moved_by_[a] + moved_by_[c]);
  };
  for (int r = 0; r + 1 < rows; ++r) {  // the cells' two triangles, as cloth_mesh.hpp lists them
    for (int c = 0; c < cell_cols; ++c) {
      const int t = 2 * (r * cell_cols + c), i = r * cols + c;
      fill(t, i, i + cols, i + 1);
      fill(t + 1, i + cols, i + cols + 1, i + 1);
    }
  }
}

// The cone of a leaf patch: about its mean normal over the step, holding every triangle's
// normal n(t) = (1 - t) n0 + t n1 - t (1 - t) du x dv at every moment t of the step, since
// n(t) . d >= min(n0 . d, n1 . d) - curl / 4 and |n(t)| <= max(|n0|, |n1|) + curl / 4.
template <typename Real>
typename SelfCollision<Real>::Cone SelfCollision<Real>::PatchCone(const ClothPatch& patch) const {
  Point sum = Point::Zero();
  for (int t : patch.triangles) sum += normals_[t].start + normals_[t].end;
  const double length = sum.norm();
  if (length == 0) return {Point::UnitZ(), kPi};
  const Point axis = sum / length;
  double least = 1;
  for (int t : patch.triangles) {
    const TriangleNormal& n = normals_[t];
    const double along = std::min(n.start.dot(axis), n.end.dot(axis)) - n.curl / 4;
    least = std::min(least, along <= 0 ? -1.0 : along / (n.longest + n.curl / 4));
  }
  return {axis, least > 0 ? std::acos(least) : kPi};
}

// Regions' boxes and cones, leaves from their triangles, the rest from their halves.
template <typename Real>
void SelfCollision<Real>::RegionBounds() {
  const std::vector<PatchRegion>& regions = patches_.regions;
  region_box_.resize(regions.size());
  region_cone_.resize(regions.size());
  for (size_t r = 0; r < regions.size(); ++r) {
    const PatchRegion& region = regions[r];
    if (region.leaf()) {
      const ClothPatch& patch = patches_.patches[region.patch];
      Box box{Point::Constant(INFINITY), Point::Constant(-INFINITY)};
      for (int t : patch.triangles) box = box.Joined(triangle_box_[t]);
      region_box_[r] = box;
      region_cone_[r] = PatchCone(patch);
    } else {
      region_box_[r] = region_box_[region.left].Joined(region_box_[region.right]);
      region_cone_[r] = Union(region_cone_[region.left], region_cone_[region.right]);
    }
  }
}

// The smallest cone holding both: its half-angle spans the two cones and the angle between
// their axes, and its axis turns from the first towards the second to centre it.
template <typename Real>
typename SelfCollision<Real>::Cone SelfCollision<Real>::Union(const Cone& a, const Cone& b) {
  if (a.half_angle >= kPi / 2 || b.half_angle >= kPi / 2) return {a.axis, kPi};
  const double between = std::acos(std::clamp(a.axis.dot(b.axis), -1.0, 1.0));
  if (between + b.half_angle <= a.half_angle) return a;
  if (between + a.half_angle <= b.half_angle) return b;
  const double half = (between + a.half_angle + b.half_angle) / 2;
  if (half >= kPi / 2) return {a.axis, kPi};
  const double turn = half - a.half_angle;
  const Point axis = std::sin(between - turn) * a.axis + std::sin(turn) * b.axis;
  return {axis.normalized(), half};
}

// A region whose cone is under 90 degrees cannot meet itself; otherwise its halves are
// examined, each alone and against each other.
template <typename Real>
void SelfCollision<Real>::SelfPairs(int r, std::vector<std::array<int, 2>>* pairs) const {
  const PatchRegion& region = patches_.regions[r];
  if (region_cone_[r].half_angle < kPi / 2) return;
  if (region.leaf()) {
    pairs->push_back({region.patch, region.patch});
    return;
  }
  SelfPairs(region.left, pairs);
  SelfPairs(region.right, pairs);
  CrossPairs(region.left, region.right, pairs);
}

// Two regions meet only if their boxes overlap, and two that touch only if their cones
// together reach 90 degrees; the larger is split until both are patches.
template <typename Real>
void SelfCollision<Real>::CrossPairs(int a, int b, std::vector<std::array<int, 2>>* pairs) const {
  const PatchRegion &first = patches_.regions[a], &second = patches_.regions[b];
  if (!region_box_[a].Overlaps(region_box_[b])) return;
  if (first.Touches(second) && Union(region_cone_[a], region_cone_[b]).half_angle < kPi / 2) return;
  if (first.leaf() && second.leaf()) {
    if (!first.Touches(second) && Separated(first.patch, second.patch)) return;
    pairs->push_back({std::min(first.patch, second.patch), std::max(first.patch, second.patch)});
  } else if (!first.leaf() && (second.leaf() || first.size() >= second.size())) {
    CrossPairs(first.left, b, pairs);
    CrossPairs(first.right, b, pairs);
  } else {
    CrossPairs(a, second.left, pairs);
    CrossPairs(a, second.right, pairs);
  }
}

// Whether a plane across the line between the patches' centres parts their swept nodes with
// room for h: boxes are loose for a tilted sheet, and two patches of one smooth sheet a cell
// apart are parted along that line by about the cell.
template <typename Real>
bool SelfCollision<Real>::Separated(int p, int q) const {
  const ClothPatch &a = patches_.patches[p], &b = patches_.patches[q];
  const auto centre = [&](const ClothPatch& patch) {
    Point sum = Point::Zero();
    for (int node : patch.nodes) sum += Start(node) + End(node);
    return Point(sum / (2.0 * patch.nodes.size()));
  };
  const Point axis = centre(b) - centre(a);
  double a_most = -INFINITY, b_least = INFINITY;
  for (int node : a.nodes) a_most = std::max({a_most, axis.dot(Start(node)), axis.dot(End(node))});
  for (int node : b.nodes) b_least = std::min({b_least, axis.dot(Start(node)), axis.dot(End(node))});
  return b_least - a_most > thickness_ * axis.norm();
}

template <typename Real>
void SelfCollision<Real>::Candidates(const std::vector<std::array<int, 2>>& patch_pairs) {
  candidates_.clear();
  for (const auto& [p, q] : patch_pairs) {
    AddPairs(p, q);
    if (p != q) AddPairs(q, p);
  }
}

// p's own nodes against q's triangles; p's own edges against q's own edges (for a patch with
// itself, each edge pair once; for two patches, called both ways, the edges once). Only the
// primitives inside the other patch's box take part.
template <typename Real>
void SelfCollision<Real>::AddPairs(int p, int q) {
  const ClothPatch &from = patches_.patches[p], &to = patches_.patches[q];
  const Box &from_box = region_box_[leaf_region_[p]], &to_box = region_box_[leaf_region_[q]];
  near_.clear();
  for (int node : from.owned_nodes) {
    if (node_box_[node].Overlaps(to_box)) near_.push_back(node);
  }
  for (int t : to.triangles) {
    if (!triangle_box_[t].Overlaps(from_box)) continue;
    for (int node : near_) {
      if (mesh_.HasCorner(t, node) || !node_box_[node].Overlaps(triangle_box_[t])) continue;
      const Pair pair{false, node, t};
      if (!Immobile(Nodes(pair))) candidates_.push_back(pair);
    }
  }
  if (p > q) return;
  near_.clear();
  for (int e : from.owned_edges) {
    if (edge_box_[e].Overlaps(to_box)) near_.push_back(e);
  }
  for (int f : to.owned_edges) {
    if (!edge_box_[f].Overlaps(from_box)) continue;
    for (int e : near_) {
      if ((p == q && f <= e) || mesh_.Adjacent(e, f) || !edge_box_[e].Overlaps(edge_box_[f])) continue;
      const Pair pair{true, std::min(e, f), std::max(e, f)};
      if (!Immobile(Nodes(pair))) candidates_.push_back(pair);
    }
  }
}

template <typename Real>
std::array<int, 4> SelfCollision<Real>::Nodes(const Pair& pair) const {
  if (pair.edges) {
    return {mesh_.edges[pair.a][0], mesh_.edges[pair.a][1], mesh_.edges[pair.b][0], mesh_.edges[pair.b][1]};
  }
  const auto [a, b, c] = mesh_.triangles[pair.b];
  return {pair.a, a, b, c};
}

template <typename Real>
bool SelfCollision<Real>::Immobile(const std::array<int, 4>& nodes) const {
  return inverse_mass_[nodes[0]] == 0 && inverse_mass_[nodes[1]] == 0 && inverse_mass_[nodes[2]] == 0 &&
         inverse_mass_[nodes[3]] == 0;
}

// Pairs closer than h at the start, moving together, are pushed apart along the line between
// their closest points.
template <typename Real>
void SelfCollision<Real>::Proximity() {
  for (const Pair& pair : candidates_) {
    const std::array<int, 4> n = Nodes(pair);
    const std::array<Point, 4> start{Start(n[0]), Start(n[1]), Start(n[2]), Start(n[3])};
    const std::array<double, 4> k = ClosestWeights(pair.edges, start);
    const Point gap = Gap(k, start);
    const double distance = gap.norm();
    if (distance >= thickness_ || distance == 0) continue;
    const Point normal = gap / distance;
    Push(n, k, normal, 0.1 * (thickness_ - distance) / dt_);
  }
}

// One pass of continuous detection over the candidates: each contact gets an impulse, or,
// when `hold`, its nodes are held. Returns the number of contacts acted on. A pair that meets
// while already parting along the normal (a graze, not a crossing) needs no impulse.
template <typename Real>
int SelfCollision<Real>::Contacts(bool hold) {
  const double tolerance = kContactTolerance * thickness_;
  int contacts = 0;
  for (const Pair& pair : candidates_) {
    const std::array<int, 4> n = Nodes(pair);
    if (Immobile(n)) continue;
    const Primitives points{{Start(n[0]), Start(n[1]), Start(n[2]), Start(n[3])},
                            {End(n[0]), End(n[1]), End(n[2]), End(n[3])}};
    const std::optional<double> when =
        pair.edges ? EdgeEdgeContact(points, tolerance) : PointTriangleContact(points, tolerance);
    if (!when) continue;
    if (hold) {
      for (int node : n) Hold(node);
      ++contacts;
      continue;
    }
    const std::array<Point, 4> at = points.At(*when);
    const std::array<double, 4> k = ClosestWeights(pair.edges, at);
    Point normal = pair.edges ? Point((at[1] - at[0]).cross(at[3] - at[2]))
                              : Point((at[2] - at[1]).cross(at[3] - at[1]));
    const Point start_gap = Gap(k, points.start);
    if (normal.squaredNorm() < 1e-24) normal = start_gap;  // parallel edges: part them as they began
    if (normal.dot(start_gap) < 0) normal = -normal;       // from the side each began on
    if (normal.squaredNorm() == 0 || !Push(n, k, normal.normalized(), 0.1 * thickness_ / dt_)) continue;
    ++contacts;
    ++stats_.contacts;
  }
  return contacts;
}

// Impulse so that the pair's relative speed along `normal` is at least `speed`.
template <typename Real>
bool SelfCollision<Real>::Push(const std::array<int, 4>& nodes, const std::array<double, 4>& weights,
                               const Point& normal, double speed) {
  double relative = 0, resistance = 0;
  for (int i = 0; i < 4; ++i) {
    relative += weights[i] * Velocity(nodes[i]).dot(normal);
    resistance += weights[i] * weights[i] * inverse_mass_[nodes[i]];
  }
  if (relative >= speed || resistance == 0) return false;
  const double impulse = (speed - relative) / resistance;
  for (int i = 0; i < 4; ++i) {
    end_.row(nodes[i]) += (dt_ * weights[i] * inverse_mass_[nodes[i]] * impulse * normal).transpose().array();
  }
  return true;
}

template <typename Real>
void SelfCollision<Real>::Hold(int node) {
  if (inverse_mass_[node] == 0 && End(node) == Start(node)) return;
  if (inverse_mass_[node] != 0) ++stats_.held;
  inverse_mass_[node] = 0;
  end_.row(node) = start_.row(node);
}

// Holds every node the corrections moved into the pole or the ground; true if there were none.
template <typename Real>
bool SelfCollision<Real>::HoldThoseInObstacles() {
  bool outside = true;
  for (int i = 0; i < int(end_.rows()); ++i) {
    if (!Moved(i)) continue;
    if (obstacles_.Inside(end_(i, 0), end_(i, 1), end_(i, 2))) {
      Hold(i);
      outside = false;
    }
  }
  return outside;
}

template class SelfCollision<float>;
template class SelfCollision<double>;

}  // namespace flagsim::sim
