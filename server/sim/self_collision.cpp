#include "server/sim/self_collision.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

#include "server/parallel/worker_pool.hpp"

namespace flagsim::sim {
namespace {

/// Elements 0, 2, 4, ... of the run of 2 count - 1 doubles at `data`.
Eigen::Map<Eigen::ArrayXd, 0, Eigen::InnerStride<2>> EveryOther(double* data, int count) {
  return {data, count};
}

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

/// Whether the first `split` points and the rest are more than h apart along x, y or z: then
/// the primitives they span are farther apart than h too (a cheap reject).
bool ApartAlongAnAxis(int split, const std::array<Point, 4>& p, double h) {
  Point first_lo = p[0], first_hi = p[0], rest_lo = p[3], rest_hi = p[3];
  for (int i = 1; i < split; ++i) {
    first_lo = first_lo.cwiseMin(p[i]);
    first_hi = first_hi.cwiseMax(p[i]);
  }
  for (int i = split; i < 3; ++i) {
    rest_lo = rest_lo.cwiseMin(p[i]);
    rest_hi = rest_hi.cwiseMax(p[i]);
  }
  return ((rest_lo - first_hi).array() > h).any() || ((first_lo - rest_hi).array() > h).any();
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
  triangle_box_.resize(mesh_.triangles.size());
  edge_box_.resize(mesh_.edges.size());
  leaf_region_.resize(patches_.patches.size());
  for (size_t r = 0; r < patches_.regions.size(); ++r) {
    if (patches_.regions[r].leaf()) leaf_region_[patches_.regions[r].patch] = int(r);
  }
}

template <typename Real>
bool SelfCollision<Real>::Resolve(const ClothModel<Real>& model, const SimParams& params, double dt,
                                  const ClothState<Real>& start, ClothState<Real>* state) {
  stats_ = {};
  stats_.passes = 1;
  thickness_ = std::min(params.thickness, kSpacingShare * std::min(double(model.dx), double(model.dy)));
  dt_ = dt;
  threads_ = std::max(1, params.threads);
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
    if (!Moved(i) && (velocity_.row(i) == integrated_velocity_.row(i)).all()) continue;
    state->x[i] = Real(end_(i, 0));
    state->y[i] = Real(end_(i, 1));
    state->z[i] = Real(end_(i, 2));
    state->vx[i] = Real(velocity_(i, 0));
    state->vy[i] = Real(velocity_(i, 1));
    state->vz[i] = Real(velocity_(i, 2));
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
  velocity_.resize(n, 3);
  inverse_mass_.resize(n);
  for (int i = 0; i < n; ++i) {
    start_.row(i) << double(start.x[i]), double(start.y[i]), double(start.z[i]);
    end_.row(i) << double(end.x[i]), double(end.y[i]), double(end.z[i]);
    velocity_.row(i) << double(end.vx[i]), double(end.vy[i]), double(end.vz[i]);
    inverse_mass_[i] = double(model.inverse_mass[i]);
  }
  integrated_ = end_;
  integrated_velocity_ = velocity_;
}

template <typename Real>
typename SelfCollision<Real>::Box SelfCollision<Real>::Box::Around(const Point& lo, const Point& hi) {
  Box box{lo.cast<float>(), hi.cast<float>()};
  for (int k = 0; k < 3; ++k) {
    if (double(box.lo[k]) > lo[k]) box.lo[k] = std::nextafter(box.lo[k], -INFINITY);
    if (double(box.hi[k]) < hi[k]) box.hi[k] = std::nextafter(box.hi[k], INFINITY);
  }
  return box;
}

template <typename Real>
void SelfCollision<Real>::SweptBoxes() {
  const Point grow = Point::Constant(thickness_ / 2);  // two boxes overlap when within h
  node_box_.resize(start_.rows());
  for (int i = 0; i < int(start_.rows()); ++i) {
    node_box_[i] = Box::Around(Start(i).cwiseMin(End(i)) - grow, Start(i).cwiseMax(End(i)) + grow);
  }
}

// The swept boxes of a patch's triangles and owned edges, their nodes' together: made only for
// the patches a pair names, as most of the flag is culled before.
template <typename Real>
void SelfCollision<Real>::BoxPatch(int p) {
  const ClothPatch& patch = patches_.patches[p];
  for (int t : patch.triangles) {
    const auto [a, b, c] = mesh_.triangles[t];
    triangle_box_[t] = node_box_[a].Joined(node_box_[b]).Joined(node_box_[c]);
  }
  for (int e : patch.owned_edges) {
    const auto [a, b] = mesh_.edges[e];
    edge_box_[e] = node_box_[a].Joined(node_box_[b]);
  }
}

// Every triangle's normal (unnormalised) at the step's start and end, the longer, and a bound
// on how far the normal strays between them: |du x dv| <= |du| |dv|, and an edge's change
// du = d_b - d_a is at most |d_a| + |d_b| for the nodes' displacements d. Row by row of cells,
// each coordinate of a row a contiguous run: the arithmetic is vectorised.
template <typename Real>
void SelfCollision<Real>::TriangleNormals() {
  const int cells = cols_ - 1, rows = int(start_.rows()) / cols_, triangles = 2 * cells * (rows - 1);
  moved_by_ = (end_ - start_).matrix().rowwise().norm();
  normal_start_.resize(triangles, 3);
  normal_end_.resize(triangles, 3);
  normal_curl_.resize(triangles);
  const auto moved = [&](int node) { return moved_by_.array().segment(node, cells); };
  ParallelFor(rows - 1, threads_, [&](int r) {
    const int top = r * cols_, bottom = top + cols_, first = 2 * r * cells;
    CellNormals(start_, top, bottom, cells, first, &normal_start_);
    CellNormals(end_, top, bottom, cells, first, &normal_end_);
    EveryOther(normal_curl_.data() + first, cells) =
        (moved(top) + moved(bottom)) * (moved(top) + moved(top + 1));
    EveryOther(normal_curl_.data() + first + 1, cells) =
        (moved(bottom) + moved(bottom + 1)) * (moved(bottom) + moved(top + 1));
  });
  normal_longest_ = normal_start_.square().rowwise().sum().max(normal_end_.square().rowwise().sum()).sqrt();
}

// The normals (b - a) x (c - a) of a row of cells' two triangles, as cloth_mesh.hpp lists them:
// (i, i + cols, i + 1) into rows first, first + 2, ... of `normals` and
// (i + cols, i + cols + 1, i + 1) into first + 1, first + 3, ..., for i from `top` on and
// i + cols from `bottom` on.
template <typename Real>
void SelfCollision<Real>::CellNormals(const Positions& x, int top, int bottom, int cells, int first,
                                      Positions* normals) {
  const auto run = [&x, cells](int k, int node) { return x.col(k).segment(node, cells); };
  for (int upper = 0; upper < 2; ++upper) {
    const int a = upper ? bottom : top, b = upper ? bottom + 1 : bottom, c = top + 1;
    const auto u = [&](int k) { return run(k, b) - run(k, a); };
    const auto v = [&](int k) { return run(k, c) - run(k, a); };
    for (int k = 0; k < 3; ++k) {
      const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
      EveryOther(normals->col(k).data() + first + upper, cells) = u(k1) * v(k2) - u(k2) * v(k1);
    }
  }
}

// The cone of a leaf patch: about its mean normal over the step, holding every triangle's
// normal n(t) = (1 - t) n0 + t n1 - t (1 - t) du x dv at every moment t of the step, since
// n(t) . d >= min(n0 . d, n1 . d) - curl / 4 and |n(t)| <= max(|n0|, |n1|) + curl / 4. The
// least of n(t) . d / |n(t)| over the triangles is the cone's cosine.
template <typename Real>
NormalCone SelfCollision<Real>::PatchCone(const ClothPatch& patch) const {
  Point sum = Point::Zero();
  for (int t : patch.triangles) sum += Row(normal_start_, t) + Row(normal_end_, t);
  const double length = sum.norm();
  if (length == 0) return {Point::UnitZ()};
  const Point axis = sum / length;
  double least = 1;
  for (int t : patch.triangles) {
    const double curl = normal_curl_[t] / 4;
    const double along = std::min(Row(normal_start_, t).dot(axis), Row(normal_end_, t).dot(axis)) - curl;
    least = std::min(least, along <= 0 ? -1.0 : along / (normal_longest_[t] + curl));
  }
  if (least <= 0) return {axis};
  return {axis, least, std::sqrt((1 - least) * (1 + least))};
}

// Regions' boxes and cones: the leaves from their nodes and triangles (in parallel), then the
// rest from their halves, which come before them.
template <typename Real>
void SelfCollision<Real>::RegionBounds() {
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
template <typename Real>
void SelfCollision<Real>::SelfPairs(int r, std::vector<std::array<int, 2>>* pairs) const {
  const PatchRegion& region = patches_.regions[r];
  if (region_cone_[r].Narrow()) return;
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
  if (first.Touches(second) && NormalCone::NarrowTogether(region_cone_[a], region_cone_[b])) return;
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

// The boxes of every patch a pair names; then each pair's candidates into a list of its own (in
// parallel), the lists joined in the pairs' order: the same candidates in the same order at any
// thread count.
template <typename Real>
void SelfCollision<Real>::Candidates(const std::vector<std::array<int, 2>>& patch_pairs) {
  boxed_.assign(patches_.patches.size(), false);
  named_.clear();
  for (const auto& pair : patch_pairs) {
    for (int p : pair) {
      if (!std::exchange(boxed_[p], true)) named_.push_back(p);
    }
  }
  ParallelFor(int(named_.size()), threads_, [&](int i) { BoxPatch(named_[i]); });
  const int count = int(patch_pairs.size());
  if (int(pair_candidates_.size()) < count) pair_candidates_.resize(count);
  near_.resize(threads_);
  ParallelForEachParticipant(count, threads_, [&](int i, int participant) {
    const auto [p, q] = patch_pairs[i];
    std::vector<Pair>& found = pair_candidates_[i];
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
template <typename Real>
void SelfCollision<Real>::AddPairs(int p, int q, std::vector<int>* near, std::vector<Pair>* found) const {
  const ClothPatch &from = patches_.patches[p], &to = patches_.patches[q];
  const Box &from_box = region_box_[leaf_region_[p]], &to_box = region_box_[leaf_region_[q]];
  near->clear();
  for (int node : from.owned_nodes) {
    if (node_box_[node].Overlaps(to_box)) near->push_back(node);
  }
  for (int t : to.triangles) {
    if (!triangle_box_[t].Overlaps(from_box)) continue;
    for (int node : *near) {
      if (mesh_.HasCorner(t, node) || !node_box_[node].Overlaps(triangle_box_[t])) continue;
      const Pair pair{false, node, t};
      if (!Immobile(Nodes(pair))) found->push_back(pair);
    }
  }
  if (p > q) return;
  near->clear();
  for (int e : from.owned_edges) {
    if (edge_box_[e].Overlaps(to_box)) near->push_back(e);
  }
  for (int f : to.owned_edges) {
    if (!edge_box_[f].Overlaps(from_box)) continue;
    for (int e : *near) {
      if ((p == q && f <= e) || mesh_.Adjacent(e, f) || !edge_box_[e].Overlaps(edge_box_[f])) continue;
      const Pair pair{true, std::min(e, f), std::max(e, f)};
      if (!Immobile(Nodes(pair))) found->push_back(pair);
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

// body(c, found) for every candidate c, in blocks shared among the threads, each block's
// finds into a list of its own; the lists joined in the candidates' order.
template <typename Real>
template <typename Found, typename Body>
void SelfCollision<Real>::ForEachCandidate(std::vector<std::vector<Found>>* blocks, std::vector<Found>* found,
                                           const Body& body) const {
  const int count = int(candidates_.size()), block_count = (count + kBlock - 1) / kBlock;
  if (int(blocks->size()) < block_count) blocks->resize(block_count);
  ParallelFor(block_count, threads_, [&](int block) {
    std::vector<Found>& mine = (*blocks)[block];
    mine.clear();
    for (int c = block * kBlock; c < std::min(count, (block + 1) * kBlock); ++c) body(c, &mine);
  });
  found->clear();
  for (int block = 0; block < block_count; ++block) {
    found->insert(found->end(), (*blocks)[block].begin(), (*blocks)[block].end());
  }
}

// Pairs closer than h at the start, moving together, are pushed apart along the line between
// their closest points. Which pairs are close depends on the start alone, so it is found in
// parallel; the impulses follow in the candidates' order.
template <typename Real>
void SelfCollision<Real>::Proximity() {
  ForEachCandidate(&proximate_blocks_, &proximate_, [this](int c, std::vector<Proximate>* found) {
    const Pair& pair = candidates_[c];
    const std::array<int, 4> n = Nodes(pair);
    const std::array<Point, 4> start{Start(n[0]), Start(n[1]), Start(n[2]), Start(n[3])};
    if (ApartAlongAnAxis(pair.edges ? 2 : 1, start, thickness_)) return;
    const std::array<double, 4> k = ClosestWeights(pair.edges, start);
    const Point gap = Gap(k, start);
    const double distance = gap.norm();
    if (distance >= thickness_ || distance == 0) return;
    found->push_back({c, k, gap / distance, 0.1 * (thickness_ - distance) / dt_});
  });
  for (const Proximate& close : proximate_)
    Push(Nodes(candidates_[close.candidate]), close.k, close.normal, close.speed);
}

// When the pair's straight paths from start to end meet within the step, if they do.
template <typename Real>
std::optional<double> SelfCollision<Real>::ContactTime(const Pair& pair, const std::array<int, 4>& n) const {
  const double tolerance = kContactTolerance * thickness_;
  const Primitives points = PathsOf(n);
  return pair.edges ? EdgeEdgeContact(points, tolerance) : PointTriangleContact(points, tolerance);
}

// One pass of continuous detection over the candidates, in their order: each contact gets an
// impulse, or, when `hold`, its nodes are held. Returns the number of contacts acted on. A pair
// that meets while already parting along the normal (a graze, not a crossing) needs no impulse.
// An impulse moves the ends of the nodes it pushes, so a pair's contact is found as the ends
// stand at its turn: first for every pair in parallel as they stand at the pass's start, then
// again at its turn for a pair whose nodes an impulse has moved since (touched_).
template <typename Real>
int SelfCollision<Real>::Contacts(bool hold) {
  ForEachCandidate(&hit_blocks_, &hits_, [this](int c, std::vector<Hit>* found) {
    const std::array<int, 4> n = Nodes(candidates_[c]);
    if (Immobile(n)) return;
    if (const std::optional<double> when = ContactTime(candidates_[c], n)) found->push_back({c, *when});
  });
  touched_.assign(start_.rows(), false);
  const auto touched = [this](const std::array<int, 4>& n) {
    return touched_[n[0]] || touched_[n[1]] || touched_[n[2]] || touched_[n[3]];
  };
  int contacts = 0;
  auto next_hit = hits_.begin();
  for (int c = 0; c < int(candidates_.size()); ++c) {
    const Pair& pair = candidates_[c];
    const bool hit_at_start = next_hit != hits_.end() && next_hit->candidate == c;
    const std::optional<double> at_start = hit_at_start ? std::optional(next_hit->when) : std::nullopt;
    if (hit_at_start) ++next_hit;
    const std::array<int, 4> n = Nodes(pair);
    if (Immobile(n)) continue;
    const std::optional<double> when = touched(n) ? ContactTime(pair, n) : at_start;
    if (!when) continue;
    if (hold) {
      for (int node : n) Hold(node);
      for (int node : n) touched_[node] = true;
      ++contacts;
      continue;
    }
    const Primitives points = PathsOf(n);
    const std::array<Point, 4> at = points.At(*when);
    const std::array<double, 4> k = ClosestWeights(pair.edges, at);
    Point normal = pair.edges ? Point((at[1] - at[0]).cross(at[3] - at[2]))
                              : Point((at[2] - at[1]).cross(at[3] - at[1]));
    const Point start_gap = Gap(k, points.start);
    if (normal.squaredNorm() < 1e-24) normal = start_gap;  // parallel edges: part them as they began
    if (normal.dot(start_gap) < 0) normal = -normal;       // from the side each began on
    if (normal.squaredNorm() == 0 || !Push(n, k, normal.normalized(), 0.1 * thickness_ / dt_)) continue;
    for (int node : n) touched_[node] = true;
    ++contacts;
    ++stats_.contacts;
  }
  return contacts;
}

// Impulse so that the pair's relative speed along `normal` is at least `speed`.
// The pair's relative normal speed over the step, sum k_i v_i . n with v_i = (x1 - x0) / dt,
// raised to `speed` by an impulse that moves the end positions; then the same for the end
// velocities, each by an impulse of its own (none if they already part at `speed`).
template <typename Real>
bool SelfCollision<Real>::Push(const std::array<int, 4>& nodes, const std::array<double, 4>& weights,
                               const Point& normal, double speed) {
  double relative = 0, relative_end = 0, resistance = 0;
  for (int i = 0; i < 4; ++i) {
    relative += weights[i] * Velocity(nodes[i]).dot(normal);
    relative_end += weights[i] * Row(velocity_, nodes[i]).dot(normal);
    resistance += weights[i] * weights[i] * inverse_mass_[nodes[i]];
  }
  if (relative >= speed || resistance == 0) return false;
  const double impulse = (speed - relative) / resistance;
  const double impulse_end = std::max(0.0, speed - relative_end) / resistance;
  for (int i = 0; i < 4; ++i) {
    const Point along = weights[i] * inverse_mass_[nodes[i]] * normal;
    end_.row(nodes[i]) += (dt_ * impulse * along).transpose().array();
    velocity_.row(nodes[i]) += (impulse_end * along).transpose().array();
  }
  return true;
}

// The fail-safe: the node stays where it began the step and ends it at rest.
template <typename Real>
void SelfCollision<Real>::Hold(int node) {
  if (inverse_mass_[node] == 0 && End(node) == Start(node) && Row(velocity_, node).isZero()) return;
  if (inverse_mass_[node] != 0) ++stats_.held;
  inverse_mass_[node] = 0;
  end_.row(node) = start_.row(node);
  velocity_.row(node).setZero();
}

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
