// The cloth never passes through itself: after each step, the motion of every node from its
// start x0 to its end x1 is corrected so that no point crosses a triangle and no edge crosses
// an edge (Bridson, Fedkiw and Anderson 2002, "Robust treatment of collisions, contact and
// friction for cloth animation", in the form of a correction after the step). README.md gives
// the whole algorithm in order, stage by stage, with its files and papers.
//
// With v = (x1 - x0) / dt each node's average velocity over the step:
//   cull       the pairs of primitives that may come within h over the step: the broad phase
//              (collision_culling.hpp), normal cones over a tree of patches and swept boxes.
//   proximity  point-triangle and edge-edge pairs closer than h at x0 and approaching get an
//              impulse that stops the approach and parts them by a tenth of the overlap per
//              step: a folded flag lies on itself h apart.
//   contact    each pair whose straight paths meet within the step (collision_geometry.hpp)
//              gets an impulse along the contact normal that stops the approach, with a small
//              separating speed; repeated, since an impulse can cause other contacts.
//   fail-safe  after kImpulseRounds rounds, the nodes of any contact left keep their start
//              positions for this step (x1 = x0) and end it at rest, and so do those the
//              impulses would put in the pole or the ground: the start had no crossings, so
//              neither does the end.
// An impulse J along n on a pair with weights k_i (point-triangle: 1, -w_a, -w_b, -w_c;
// edge-edge: 1 - s, s, -(1 - t), -t) changes v_i by k_i J n / m_i, pinned and held nodes
// excepted, and the pair's relative normal speed by J sum k_i^2 / m_i.
//
// Two velocities take the impulses. The average over the step, v = (x1 - x0) / dt, decides
// whether the paths meet, and its change moves the end: x1 += dt dv. The end velocity v1 gets
// an impulse of its own along the same normal, only as much as stops its own approach: over a
// step of many substeps v1 can differ much from v (a fly edge whipping round), and adding v's
// change to it threw nodes back faster than they came (at 256 x 192 end speeds gained 4 to
// 9 m/s a step, until a spring stretched six-fold). So a correction never speeds a pair's
// parting beyond the small separating speed, and a step where nothing comes close is left
// unchanged bit for bit.
//
// Threads (params.threads) share what reads and writes nothing another part needs: the broad
// phase (collision_culling.hpp), and the detection of close pairs and of contacts in blocks of
// candidates. The impulses go one by one in the candidates' order, and a contact found before
// an impulse moved one of its nodes is found again: the same state gives the same result at
// any thread count.
#pragma once

#include <algorithm>
#include <array>
#include <optional>
#include <vector>

#include "server/sim/cloth_model.hpp"
#include "server/sim/cloth_state.hpp"
#include "server/sim/collision/collision_culling.hpp"
#include "server/sim/collision/collision_geometry.hpp"
#include "server/sim/collision/obstacles.hpp"
#include "server/sim/collision/primitive_pair.hpp"
#include "server/sim/sim_params.hpp"

namespace flagsim::sim {

/// What the last Resolve did; for a step, the sum over its passes.
struct SelfCollisionStats {
  int passes = 0;       ///< Resolve calls
  int patch_pairs = 0;  ///< pairs of patches examined (a patch with itself counts once)
  int candidates = 0;   ///< primitive pairs whose swept boxes overlap, first round
  int contacts = 0;     ///< impulses applied, all rounds
  int rounds = 0;       ///< the most of any pass
  int held = 0;         ///< nodes kept at their start positions by the fail-safe
  int moved = 0;        ///< nodes whose step was corrected

  SelfCollisionStats& operator+=(const SelfCollisionStats& pass) {
    passes += pass.passes;
    patch_pairs += pass.patch_pairs;
    candidates += pass.candidates;
    contacts += pass.contacts;
    rounds = std::max(rounds, pass.rounds);
    held += pass.held;
    moved += pass.moved;
    return *this;
  }
};

template <typename Real>
class SelfCollision {
 public:
  static constexpr int kImpulseRounds = 6;          ///< rounds of impulses before the fail-safe
  static constexpr double kContactTolerance = 0.1;  ///< of h: how near counts as a contact
  static constexpr double kSpacingShare = 0.25;     ///< h is at most this share of the grid spacing
  /// Of the overlap h - d: how far a proximity impulse parts a pair d apart per step.
  static constexpr double kProximityShare = 0.1;
  /// Of h: how far the parting speed a contact impulse leaves moves a pair apart per step.
  static constexpr double kPartingShare = 0.1;
  /// m^4: a contact normal (two edges' cross product, a triangle's (b - a) x (c - a)) whose
  /// squared length is under this has no direction: the edges are parallel, the triangle flat.
  static constexpr double kParallelEdges = 1e-24;

  explicit SelfCollision(const ClothModel<Real>& model);

  /// Corrects `state` (the end of a step of dt from positions `start`) as above. Returns
  /// whether anything changed.
  bool Resolve(const ClothModel<Real>& model, const SimParams& params, double dt,
               const ClothState<Real>& start, ClothState<Real>* state);

  const SelfCollisionStats& stats() const { return stats_; }

 private:
  void Load(const ClothModel<Real>& model, const ClothState<Real>& start, const ClothState<Real>& end);
  std::array<int, 4> Nodes(const PrimitivePair& pair) const { return culling_.Nodes(pair); }
  /// This round's candidates, from the culling.
  const std::vector<PrimitivePair>& candidates() const { return culling_.candidates(); }
  /// Candidates a thread takes at a time in the detection passes.
  static constexpr int kBlock = 256;
  template <typename Found, typename Body>
  void ForEachCandidate(std::vector<std::vector<Found>>* blocks, std::vector<Found>* found,
                        const Body& body) const;
  /// A candidate closer than h at the start: its weights, the normal and the parting speed it is due.
  struct Proximate {
    int candidate = 0;
    std::array<double, 4> k{};
    Point normal;
    double speed = 0;
  };
  void Proximity();
  /// A candidate whose paths meet, and when (a fraction of the step).
  struct Hit {
    int candidate = 0;
    double when = 0;
  };
  std::optional<double> ContactTime(int candidate, const std::array<int, 4>& nodes) const;
  /// Of the tolerance: room for the rounding of a start gap (ContactTime).
  static constexpr double kGapMargin = 1e-6;
  int Contacts(bool hold);
  bool HoldThoseInObstacles();
  bool Push(const std::array<int, 4>& nodes, const std::array<double, 4>& weights, const Point& normal,
            double speed);
  void Hold(int node);
  Point Start(int node) const { return Row(start_, node); }
  Point End(int node) const { return Row(end_, node); }
  static Point Row(const NodeRows& rows, int i) { return rows.row(i).transpose().matrix(); }
  Point Velocity(int node) const { return (End(node) - Start(node)) / dt_; }
  double Moved(int node) const { return (End(node) - Start(node)).norm(); }
  /// The nodes' straight paths over the step.
  Primitives PathsOf(const std::array<int, 4>& n) const {
    return {{Start(n[0]), Start(n[1]), Start(n[2]), Start(n[3])},
            {End(n[0]), End(n[1]), End(n[2]), End(n[3])}};
  }

  CollisionCulling culling_;
  Obstacles obstacles_;
  double thickness_ = 0, dt_ = 0;
  int threads_ = 1;  ///< params.threads: the same result at any count

  // Per step, per node: positions at the start and end (as corrected), the end velocity (as
  // corrected), inverse mass (0 when pinned or held); whether an impulse or the fail-safe has
  // touched its end or end velocity (else they are as the integrator left them), and whether
  // its end moved (only then can it have entered an obstacle: the pinned hoist nodes lie on
  // the pole's surface, and a touch that moves nothing must not call them inside).
  NodeRows start_, end_, velocity_;
  std::vector<double> inverse_mass_;
  std::vector<char> changed_, moved_;
  bool start_is_culled_end_ = false;  ///< start_ is the end_ the culling last saw (Load)
  std::vector<std::vector<Proximate>> proximate_blocks_;
  std::vector<Proximate> proximate_;
  std::vector<std::vector<Hit>> hit_blocks_;
  std::vector<Hit> hits_;      ///< contacts as the ends stood when the pass began, in order
  std::vector<char> touched_;  ///< per node: moved by an impulse or held in this pass
  /// Per candidate of the first round: the distance between its primitives at the start as
  /// Proximity found it, or h where an axis parts them by more.
  std::vector<double> start_gap_;
  SelfCollisionStats stats_;
};

}  // namespace flagsim::sim
