// The broad phase misses nothing: every pair of primitives that comes within h of each other at
// some moment of a step is a candidate, checked against every pair of the mesh by brute force.
#include "server/sim/collision/collision_culling.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <tuple>
#include <vector>

namespace flagsim::sim {
namespace {

constexpr int kCols = 14, kRows = 10;
constexpr double kSpacing = 0.1, kH = kSpacing / 4;
constexpr int kSamples = 64;  ///< moments of the step the brute force looks at

/// A sheet folded in two across its columns, the far half above the near one and shifted by a
/// third of a cell, each node jittered: the far half comes down from 2.4 h to about h above the
/// near one over the step, and every node wanders a little.
void FoldedSheet(std::mt19937* random, NodeRows* start, NodeRows* end) {
  std::uniform_real_distribution<double> jitter(-0.3 * kH, 0.3 * kH);
  start->resize(kCols * kRows, 3);
  end->resize(kCols * kRows, 3);
  for (int r = 0; r < kRows; ++r) {
    for (int c = 0; c < kCols; ++c) {
      const bool far = c >= kCols / 2;
      const double x = far ? (kCols - 1 - c) * kSpacing + kSpacing / 3 : c * kSpacing, y = r * kSpacing;
      const int i = r * kCols + c;
      start->row(i) << x + jitter(*random), y + jitter(*random), (far ? 2.4 * kH : 0) + jitter(*random);
      end->row(i) << x + jitter(*random), y + jitter(*random), (far ? 1.1 * kH : 0) + jitter(*random);
    }
  }
}

Point At(const NodeRows& start, const NodeRows& end, int node, double t) {
  return ((1 - t) * start.row(node) + t * end.row(node)).transpose().matrix();
}

/// Whether the pair's nodes (point, triangle or edge, edge) come within h at a sampled moment.
bool ComesNear(bool edges, const std::array<int, 4>& n, const NodeRows& start, const NodeRows& end) {
  for (int k = 0; k <= kSamples; ++k) {
    const double t = double(k) / kSamples;
    std::array<Point, 4> p;
    for (int i = 0; i < 4; ++i) p[i] = At(start, end, n[i], t);
    Point gap;
    if (edges) {
      const SegmentParameters c = ClosestOnSegments(p[0], p[1], p[2], p[3]);
      gap = (p[0] + c.s * (p[1] - p[0])) - (p[2] + c.t * (p[3] - p[2]));
    } else {
      const Eigen::Vector3d w = ClosestOnTriangle(p[0], p[1], p[2], p[3]);
      gap = p[0] - (w[0] * p[1] + w[1] * p[2] + w[2] * p[3]);
    }
    if (gap.norm() < kH) return true;
  }
  return false;
}

using PairKey = std::tuple<bool, int, int>;

TEST(CollisionCulling, EveryPairThatComesWithinHIsACandidate) {
  const ClothMesh mesh = BuildClothMesh(kCols, kRows);
  std::vector<double> inverse_mass(kCols * kRows, 1.0);
  for (int r = 0; r < kRows; ++r) inverse_mass[r * kCols] = 0;  // the hoist edge, pinned
  CollisionCulling culling(kCols, kRows);
  std::mt19937 random(11);
  int near_pairs = 0, candidates = 0, all_pairs = 0;
  for (int trial = 0; trial < 6; ++trial) {
    NodeRows start, end;
    FoldedSheet(&random, &start, &end);
    std::set<PairKey> found;
    for (const PrimitivePair& pair : culling.Find(start, end, inverse_mass, kH, 1)) {
      found.insert({pair.edges, pair.a, pair.b});
    }
    candidates += int(found.size());
    for (int node = 0; node < kCols * kRows; ++node) {
      for (int t = 0; t < int(mesh.triangles.size()); ++t) {
        if (mesh.HasCorner(t, node)) continue;
        ++all_pairs;
        const auto [a, b, c] = mesh.triangles[t];
        if (!ComesNear(false, {node, a, b, c}, start, end)) continue;
        ++near_pairs;
        EXPECT_TRUE(found.count({false, node, t})) << "node " << node << ", triangle " << t;
      }
    }
    for (int e = 0; e < int(mesh.edges.size()); ++e) {
      for (int f = e + 1; f < int(mesh.edges.size()); ++f) {
        if (mesh.Adjacent(e, f)) continue;
        ++all_pairs;
        const std::array<int, 4> n{mesh.edges[e][0], mesh.edges[e][1], mesh.edges[f][0], mesh.edges[f][1]};
        if (!ComesNear(true, n, start, end)) continue;
        ++near_pairs;
        EXPECT_TRUE(found.count({true, e, f})) << "edges " << e << " and " << f;
      }
    }
  }
  // Not vacuous: the fold brings many pairs within h, and the culling still leaves out most pairs.
  EXPECT_GT(near_pairs, 500);
  EXPECT_LT(candidates, all_pairs / 20);
}

/// The same pairs in the same order, and some.
void ExpectSameCandidates(const std::vector<PrimitivePair>& found,
                          const std::vector<PrimitivePair>& expected) {
  ASSERT_EQ(found.size(), expected.size());
  for (size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(std::tie(found[i].edges, found[i].a, found[i].b),
              std::tie(expected[i].edges, expected[i].a, expected[i].b));
  }
  EXPECT_FALSE(expected.empty());
}

TEST(CollisionCulling, TheSameCandidatesInTheSameOrderAtAnyThreadCount) {
  std::vector<double> inverse_mass(kCols * kRows, 1.0);
  std::mt19937 random(5);
  NodeRows start, end;
  FoldedSheet(&random, &start, &end);
  CollisionCulling one(kCols, kRows), two(kCols, kRows);
  ExpectSameCandidates(two.Find(start, end, inverse_mass, kH, 2), one.Find(start, end, inverse_mass, kH, 1));
}

// A step that starts where the last one ended takes over its end normals: the candidates are
// those of a culling that works every normal out afresh. The last step unfolds the sheet from
// flat, so normals kept from its start instead would widen the cones and add candidates.
TEST(CollisionCulling, AStepThatStartsWhereTheLastEndedFindsWhatAFreshStartFinds) {
  std::vector<double> inverse_mass(kCols * kRows, 1.0);
  std::mt19937 random(9);
  NodeRows flat, start, end;
  FoldedSheet(&random, &start, &end);
  flat = start;
  for (int r = 0; r < kRows; ++r) {
    for (int c = 0; c < kCols; ++c) flat.row(r * kCols + c) << c * kSpacing, r * kSpacing, 0;
  }
  CollisionCulling carried(kCols, kRows), fresh(kCols, kRows);
  carried.Find(flat, start, inverse_mass, kH, 1);
  ExpectSameCandidates(carried.Find(start, end, inverse_mass, kH, 1, true),
                       fresh.Find(start, end, inverse_mass, kH, 1));
}

// A sheet folded in two, the far half 3 h above the near one and shifted by a third of a cell,
// tilted 45 degrees about y so that boxes of the two layers overlap. Only the patches that hold
// the fold have anything within h of the other layer. Two flat patches of the layers a cell
// apart sideways are not parted across the line between their centres, but across their mean
// normal they are: no pair of them is examined.
TEST(CollisionCulling, FlatLayersOfAFoldMoreThanHApartAreNotExamined) {
  std::vector<double> inverse_mass(kCols * kRows, 1.0);
  NodeRows sheet(kCols * kRows, 3);
  const double tilt = M_PI / 4;
  for (int r = 0; r < kRows; ++r) {
    for (int c = 0; c < kCols; ++c) {
      const bool far = c >= kCols / 2;
      const double x = far ? (kCols - 1 - c) * kSpacing + kSpacing / 3 : c * kSpacing, z = far ? 3 * kH : 0;
      sheet.row(r * kCols + c) << x * std::cos(tilt) - z * std::sin(tilt), r * kSpacing,
          x * std::sin(tilt) + z * std::cos(tilt);
    }
  }
  CollisionCulling culling(kCols, kRows);
  culling.Find(sheet, sheet, inverse_mass, kH, 1);
  // Patches of 2 x 2 cells, numbered row by row; the fold is in patch column 3 (nodes 6 to 8).
  constexpr int kCells = kCols - 1, kPatchCols = (kCells + 1) / 2, kFoldColumn = 3;
  for (const auto& [p, q] : culling.patch_pairs()) {
    EXPECT_TRUE(p % kPatchCols == kFoldColumn || q % kPatchCols == kFoldColumn)
        << "patches " << p << ", " << q;
  }
  EXPECT_FALSE(culling.patch_pairs().empty());
}

// A flat sheet but for one cell whose four nodes lie on one point: its triangles have no
// normal, so no cone can hold them, and its patch is examined against itself.
TEST(CollisionCulling, APatchWithACollapsedCellIsExamined) {
  std::vector<double> inverse_mass(kCols * kRows, 1.0);
  NodeRows sheet(kCols * kRows, 3);
  for (int r = 0; r < kRows; ++r) {
    for (int c = 0; c < kCols; ++c) sheet.row(r * kCols + c) << c * kSpacing, r * kSpacing, 0;
  }
  // Cell (row 5, column 9): patch (2, 4), numbered row by row.
  constexpr int kCellRow = 5, kCellCol = 9, kCells = kCols - 1, kPatchCols = (kCells + 1) / 2;
  for (const int node : {0, 1, kCols, kCols + 1})
    sheet.row(kCellRow * kCols + kCellCol + node) = sheet.row(kCellRow * kCols + kCellCol);
  CollisionCulling culling(kCols, kRows);
  culling.Find(sheet, sheet, inverse_mass, kH, 1);
  const int patch = (kCellRow / 2) * kPatchCols + kCellCol / 2;
  const std::vector<std::array<int, 2>>& pairs = culling.patch_pairs();
  EXPECT_NE(std::find(pairs.begin(), pairs.end(), std::array<int, 2>{patch, patch}), pairs.end());
}

}  // namespace
}  // namespace flagsim::sim
