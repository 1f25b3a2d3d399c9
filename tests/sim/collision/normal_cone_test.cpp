// Cones of normals: the union holds both cones and is the smallest that does, and the cheap
// narrowness test agrees with the union's.
#include "server/sim/collision/normal_cone.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>

#include "server/sim/collision/lane_layout.hpp"

namespace flagsim::sim {
namespace {

NormalCone ConeOf(const Point& axis, double half_angle) {
  return {axis.normalized(), std::cos(half_angle), std::sin(half_angle)};
}

/// A direction on the rim of `cone`, at `turn` radians round its axis.
Point Rim(const NormalCone& cone, double turn) {
  const Point side = cone.axis.unitOrthogonal(), other = cone.axis.cross(side);
  return cone.cos_half * cone.axis + cone.sin_half * (std::cos(turn) * side + std::sin(turn) * other);
}

double HalfAngle(const NormalCone& cone) { return std::atan2(cone.sin_half, cone.cos_half); }

TEST(NormalCone, TheUnionHoldsBothAndIsNoWiderThanItMustBe) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(-1, 1), angle(0.01, 1.4);
  int narrow = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const NormalCone a = ConeOf({unit(random), unit(random), unit(random)}, angle(random));
    const NormalCone b = ConeOf({unit(random), unit(random), unit(random)}, angle(random));
    const NormalCone both = NormalCone::Union(a, b);
    EXPECT_EQ(both.Narrow(), NormalCone::NarrowTogether(a, b));
    if (!both.Narrow()) continue;
    ++narrow;
    EXPECT_NEAR(both.axis.norm(), 1, 1e-12);
    for (int k = 0; k < 16; ++k) {
      const double turn = 2 * M_PI * k / 16;
      EXPECT_GE(Rim(a, turn).dot(both.axis), both.cos_half - 1e-9);
      EXPECT_GE(Rim(b, turn).dot(both.axis), both.cos_half - 1e-9);
    }
    // Tight: half of beta + ta + tb, or the wider cone when it holds the other.
    const double beta = std::acos(std::clamp(a.axis.dot(b.axis), -1.0, 1.0));
    const double expected = std::max({(beta + HalfAngle(a) + HalfAngle(b)) / 2, HalfAngle(a), HalfAngle(b)});
    EXPECT_NEAR(HalfAngle(both), expected, 1e-9);
  }
  EXPECT_GT(narrow, 200);  // the trials reached the narrow case often
}

TEST(NormalCone, LanesAreJoinedEachOnItsOwn) {
  std::mt19937 random(11);
  std::uniform_real_distribution<double> unit(-1, 1), angle(0.01, 1.4);
  for (int trial = 0; trial < 200; ++trial) {
    ConeLanes a, b;
    std::array<NormalCone, ConeLanes::kLanes> alone;
    for (int lane = 0; lane < ConeLanes::kLanes; ++lane) {
      const NormalCone x = ConeOf({unit(random), unit(random), unit(random)}, angle(random));
      const NormalCone y = ConeOf({unit(random), unit(random), unit(random)}, angle(random));
      a.Set(lane, x);
      b.Set(lane, y);
      alone[lane] = NormalCone::Union(x, y);
    }
    const ConeLanes both = ConeLanes::Union(a, b);
    for (int lane = 0; lane < ConeLanes::kLanes; ++lane) {
      const NormalCone cone = both.Cone(lane);
      EXPECT_EQ(cone.axis, alone[lane].axis);
      EXPECT_EQ(cone.cos_half, alone[lane].cos_half);
      EXPECT_EQ(cone.sin_half, alone[lane].sin_half);
    }
  }
}

TEST(NormalCone, ACommonAxisGivesTheWiderAndOppositeAxesNothingNarrow) {
  const NormalCone wide = ConeOf(Point::UnitY(), 0.6), slim = ConeOf(Point::UnitY(), 0.2);
  EXPECT_EQ(NormalCone::Union(wide, slim).cos_half, wide.cos_half);
  EXPECT_EQ(NormalCone::Union(slim, wide).cos_half, wide.cos_half);
  EXPECT_FALSE(NormalCone::NarrowTogether(ConeOf(Point::UnitY(), 0.1), ConeOf(-Point::UnitY(), 0.1)));
  EXPECT_FALSE(NormalCone::Union(NormalCone{}, slim).Narrow());  // the open cone holds every direction
}

}  // namespace
}  // namespace flagsim::sim
