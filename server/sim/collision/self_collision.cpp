#include "server/sim/collision/self_collision.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>
#include <utility>

#include "server/parallel/worker_pool.hpp"
#include "server/sim/collision/axis_span.hpp"

namespace flagsim::sim {
namespace {

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
  for (int k = 0; k < 3; ++k) {
    AxisSpan first, rest;
    for (int i = 0; i < split; ++i) first.Add(p[i][k]);
    for (int i = split; i < 4; ++i) rest.Add(p[i][k]);
    if (Apart(first, rest, h)) return true;
  }
  return false;
}

/// sum k_i p_i: from the second primitive's closest point to the first's.
Point Gap(const std::array<double, 4>& k, const std::array<Point, 4>& p) {
  return k[0] * p[0] + k[1] * p[1] + k[2] * p[2] + k[3] * p[3];
}

}  // namespace

template <typename Real>
SelfCollision<Real>::SelfCollision(const ClothModel<Real>& model) : culling_(model.cols, model.rows) {}

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
    culling_.Find(start_, end_, inverse_mass_, thickness_, threads_, round == 0 && start_is_culled_end_);
    if (round == 0) {
      stats_.patch_pairs = int(culling_.patch_pairs().size());
      stats_.candidates = int(candidates().size());
      if (candidates().empty()) return false;
      Proximity();
    } else {
      start_gap_.clear();  // Proximity's gaps are of the first round's candidates
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
    if (!changed_[i]) continue;
    const std::array<Real, 6> corrected{Real(end_(i, 0)),      Real(end_(i, 1)),      Real(end_(i, 2)),
                                        Real(velocity_(i, 0)), Real(velocity_(i, 1)), Real(velocity_(i, 2))};
    const std::array<Real, 6> integrated{state->x[i],  state->y[i],  state->z[i],
                                         state->vx[i], state->vy[i], state->vz[i]};
    if (corrected == integrated) continue;  // impulses too small to change a Real
    state->x[i] = corrected[0];
    state->y[i] = corrected[1];
    state->z[i] = corrected[2];
    state->vx[i] = corrected[3];
    state->vy[i] = corrected[4];
    state->vz[i] = corrected[5];
    ++stats_.moved;
    changed = true;
  }
  return changed;
}

template <typename Real>
void SelfCollision<Real>::Load(const ClothModel<Real>& model, const ClothState<Real>& start,
                               const ClothState<Real>& end) {
  const int n = model.num_nodes();
  const auto column = [n](const std::vector<Real>& values) {
    return Eigen::Map<const Eigen::Array<Real, Eigen::Dynamic, 1>>(values.data(), n).template cast<double>();
  };
  const bool unchanged_since_culled =
      end_.rows() == n && std::memchr(changed_.data(), true, changed_.size()) == nullptr;
  start_.resize(n, 3);
  end_.resize(n, 3);
  velocity_.resize(n, 3);
  start_ << column(start.x), column(start.y), column(start.z);
  // The culling's end normals are this interval's start normals when the last interval's end,
  // untouched by any impulse since it was culled, is where this one starts, bit for bit.
  start_is_culled_end_ =
      unchanged_since_culled && std::memcmp(start_.data(), end_.data(), sizeof(double) * 3 * n) == 0;
  end_ << column(end.x), column(end.y), column(end.z);
  velocity_ << column(end.vx), column(end.vy), column(end.vz);
  inverse_mass_.assign(model.inverse_mass.begin(), model.inverse_mass.end());
  changed_.assign(n, false);
  moved_.assign(n, false);
}

// body(c, found) for every candidate c, in blocks shared among the threads, each block's
// finds into a list of its own; the lists joined in the candidates' order.
template <typename Real>
template <typename Found, typename Body>
void SelfCollision<Real>::ForEachCandidate(std::vector<std::vector<Found>>* blocks, std::vector<Found>* found,
                                           const Body& body) const {
  const int count = int(candidates().size()), block_count = (count + kBlock - 1) / kBlock;
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
  start_gap_.resize(candidates().size());
  ForEachCandidate(&proximate_blocks_, &proximate_, [this](int c, std::vector<Proximate>* found) {
    const PrimitivePair& pair = candidates()[c];
    const std::array<int, 4> n = Nodes(pair);
    const std::array<Point, 4> start{Start(n[0]), Start(n[1]), Start(n[2]), Start(n[3])};
    start_gap_[c] = thickness_;
    if (ApartAlongAnAxis(pair.first_nodes(), start, thickness_)) return;
    const std::array<double, 4> k = ClosestWeights(pair.edges, start);
    const Point gap = Gap(k, start);
    const double distance = gap.norm();
    start_gap_[c] = distance;
    if (distance >= thickness_ || distance == 0) return;
    found->push_back({c, k, gap / distance, kProximityShare * (thickness_ - distance) / dt_});
  });
  for (const Proximate& close : proximate_)
    Push(Nodes(candidates()[close.candidate]), close.k, close.normal, close.speed);
}

// When the pair's straight paths from start to end meet within the step, if they do. A point of
// a primitive moves by at most the most any of its nodes moves, so the primitives stay at least
// their start gap less the two primitives' largest moves apart: when that is more than the
// tolerance, they cannot meet (most pairs of a fold's two layers, which lie near each other).
template <typename Real>
std::optional<double> SelfCollision<Real>::ContactTime(int candidate, const std::array<int, 4>& n) const {
  const PrimitivePair& pair = candidates()[candidate];
  const double tolerance = kContactTolerance * thickness_;
  if (candidate < int(start_gap_.size())) {
    const double first = std::max(Moved(n[0]), pair.edges ? Moved(n[1]) : 0.0);
    const double rest = std::max({pair.edges ? 0.0 : Moved(n[1]), Moved(n[2]), Moved(n[3])});
    // The gap found is off the true one by rounding at most: a margin for it.
    if (start_gap_[candidate] - first - rest > tolerance * (1 + kGapMargin)) return std::nullopt;
  }
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
    const std::array<int, 4> n = Nodes(candidates()[c]);
    if (Immobile(n, inverse_mass_)) return;
    if (const std::optional<double> when = ContactTime(c, n)) found->push_back({c, *when});
  });
  touched_.assign(start_.rows(), false);
  const auto touched = [this](const std::array<int, 4>& n) {
    return touched_[n[0]] || touched_[n[1]] || touched_[n[2]] || touched_[n[3]];
  };
  int contacts = 0;
  auto next_hit = hits_.begin();
  for (int c = 0; c < int(candidates().size()); ++c) {
    const PrimitivePair& pair = candidates()[c];
    const bool hit_at_start = next_hit != hits_.end() && next_hit->candidate == c;
    const std::optional<double> at_start = hit_at_start ? std::optional(next_hit->when) : std::nullopt;
    if (hit_at_start) ++next_hit;
    const std::array<int, 4> n = Nodes(pair);
    if (Immobile(n, inverse_mass_)) continue;
    const std::optional<double> when = touched(n) ? ContactTime(c, n) : at_start;
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
    if (normal.squaredNorm() < kParallelEdges) normal = start_gap;  // parallel edges: part them as they began
    if (normal.dot(start_gap) < 0) normal = -normal;                // from the side each began on
    if (normal.squaredNorm() == 0 || !Push(n, k, normal.normalized(), kPartingShare * thickness_ / dt_))
      continue;
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
    const int n = nodes[i];
    const Point along = weights[i] * inverse_mass_[n] * normal;
    const Eigen::Array<double, 1, 3> before = end_.row(n);
    end_.row(n) += (dt_ * impulse * along).transpose().array();
    velocity_.row(n) += (impulse_end * along).transpose().array();
    moved_[n] = moved_[n] || (end_.row(n) != before).any();
    changed_[n] = true;
  }
  return true;
}

// The fail-safe: the node stays where it began the step and ends it at rest.
template <typename Real>
void SelfCollision<Real>::Hold(int node) {
  if (inverse_mass_[node] == 0 && End(node) == Start(node) && Row(velocity_, node).isZero()) return;
  if (inverse_mass_[node] != 0) ++stats_.held;
  inverse_mass_[node] = 0;
  moved_[node] = moved_[node] || (end_.row(node) != start_.row(node)).any();
  end_.row(node) = start_.row(node);
  velocity_.row(node).setZero();
  changed_[node] = true;
}

template <typename Real>
bool SelfCollision<Real>::HoldThoseInObstacles() {
  bool outside = true;
  for (int i = 0; i < int(end_.rows()); ++i) {
    if (!moved_[i]) continue;
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
