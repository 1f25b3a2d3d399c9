// Cones of normals: the union holds both cones and is the smallest that does, the cheap
// narrowness test agrees with the union's, and the culling's union in vector lanes agrees with
// the union by angles.
#include "server/sim/collision/normal_cone.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

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

/// rad: how far the lanes' union may be from the union by angles, on the half-angle and the
/// axis. The lanes take the angle beta between the axes from its cosine, a dot product off by a
/// few units of 2^-53: near beta = 0 that moves beta by up to sqrt(2 x 4 x 2^-53), about 3e-8
/// rad, and the union by up to that. Elsewhere they agree to some 1e-15 rad.
constexpr double kLanesTolerance = 1e-7;
/// rad: the union by angles against its own statement (acos, atan2 and unit vectors rounded).
constexpr double kReferenceTolerance = 1e-12;
constexpr int kRimPoints = 16;  ///< directions round a cone's rim that must lie in the union

double AngleBetween(const Point& u, const Point& v) { return std::atan2(u.cross(v).norm(), u.dot(v)); }

/// A unit vector `angle` from `axis`, turned `turn` about it.
Point Tilted(const Point& axis, double angle, double turn) { return Rim(ConeOf(axis, angle), turn); }

/// The half-angle of the smallest cone holding two narrow cones, as the statement gives it:
/// the wider one's when it holds the other, else half of beta + ta + tb.
double UnionHalfAngle(const NormalCone& a, const NormalCone& b) {
  const double beta = AngleBetween(a.axis, b.axis);
  return std::max({(beta + HalfAngle(a) + HalfAngle(b)) / 2, HalfAngle(a), HalfAngle(b)});
}

struct ConePair {
  NormalCone a, b;
};

/// Random cones, then the edges where the unions' cases meet: axes all but parallel (where the
/// lanes lose most) or opposite, one cone all but holding the other, unions all but 90 degrees
/// wide, cones of a single direction, of exactly 90 degrees, open cones, axes along x, y and z.
std::vector<ConePair> RandomAndAdversarialPairs() {
  std::mt19937 random(2002);
  std::normal_distribution<double> gaussian;
  std::uniform_real_distribution<double> unit(0, 1);
  const auto direction = [&] {
    return Point(gaussian(random), gaussian(random), gaussian(random)).normalized();
  };
  const auto angle = [&](double most) { return most * unit(random); };
  const auto turn = [&] { return 2 * M_PI * unit(random); };
  std::vector<ConePair> pairs;
  for (int i = 0; i < 4000; ++i)
    pairs.push_back({ConeOf(direction(), angle(M_PI / 2)), ConeOf(direction(), angle(M_PI / 2))});
  for (double beta : {0.0, 1e-15, 1e-12, 1e-10, 1e-9, 3e-9, 1e-8, 2e-8, 3e-8, 1e-7, 1e-6, 1e-4, 1e-2}) {
    for (int i = 0; i < 100; ++i) {
      const Point axis = direction();
      const double ta = angle(M_PI / 2), tb = i % 2 ? ta : angle(M_PI / 2);  // equal: neither holds the other
      pairs.push_back({ConeOf(axis, ta), ConeOf(Tilted(axis, beta, turn()), tb)});
      pairs.push_back({ConeOf(axis, ta), ConeOf(Tilted(-axis, beta, turn()), tb)});  // opposite
    }
  }
  for (double off : {-1e-9, -1e-12, 0.0, 1e-12, 1e-9}) {
    for (int i = 0; i < 100; ++i) {
      const Point axis = direction();
      const double beta = angle(0.7), tb = angle(0.7),
                   ta = std::max(0.0, beta + tb + off);  // a all but holds b
      pairs.push_back({ConeOf(axis, ta), ConeOf(Tilted(axis, beta, turn()), tb)});
      pairs.push_back({ConeOf(Tilted(axis, beta, turn()), tb), ConeOf(axis, ta)});
      const double wide = angle(M_PI / 2), narrow = angle(M_PI / 2);  // beta + ta + tb all but 180 degrees
      const double apart = std::clamp(M_PI - wide - narrow + off, 0.0, M_PI);
      pairs.push_back({ConeOf(axis, wide), ConeOf(Tilted(axis, apart, turn()), narrow)});
    }
  }
  const NormalCone single{direction(), 1, 0}, right_angle{direction(), 0, 1}, open{direction()};
  const NormalCone tiny = ConeOf(direction(), 1e-9), almost_right = ConeOf(direction(), M_PI / 2 - 1e-9);
  const std::vector<NormalCone> special{single,
                                        right_angle,
                                        open,
                                        tiny,
                                        almost_right,
                                        ConeOf(Point::UnitX(), 0.3),
                                        ConeOf(Point::UnitY(), 0.3),
                                        ConeOf(-Point::UnitZ(), 0.3),
                                        ConeOf(Point::UnitZ(), 0.3)};
  for (const NormalCone& a : special) {
    for (const NormalCone& b : special) pairs.push_back({a, b});
    for (int i = 0; i < 20; ++i) pairs.push_back({a, ConeOf(direction(), angle(M_PI / 2))});
  }
  return pairs;
}

struct Agreement {
  double half_angle = 0, axis = 0;  ///< rad, the most the lanes were off
  int joined = 0, held = 0, open = 0, at_right_angle = 0;
};

/// The lanes' union of a pair against the union by angles; the union by angles against its
/// statement.
void ExpectAgree(const ConePair& pair, const NormalCone& lanes, Agreement* agreement) {
  const NormalCone exact = NormalCone::UnionByAngles(pair.a, pair.b);
  if (!pair.a.Narrow() || !pair.b.Narrow()) {
    EXPECT_FALSE(exact.Narrow());
    EXPECT_FALSE(lanes.Narrow());
    ++agreement->open;
    return;
  }
  const double half_angle = UnionHalfAngle(pair.a, pair.b);
  if (lanes.Narrow() != exact.Narrow()) {  // only at the edge of narrow
    EXPECT_NEAR(half_angle, M_PI / 2, kLanesTolerance);
    ++agreement->at_right_angle;
    return;
  }
  if (!exact.Narrow()) {
    EXPECT_GE(half_angle, M_PI / 2 - kReferenceTolerance);
    ++agreement->open;
    return;
  }
  if (HalfAngle(exact) > std::max(HalfAngle(pair.a), HalfAngle(pair.b))) {
    ++agreement->joined;
  } else {
    ++agreement->held;
  }
  EXPECT_NEAR(HalfAngle(exact), half_angle, kReferenceTolerance);
  EXPECT_NEAR(exact.axis.norm(), 1, kReferenceTolerance);
  EXPECT_NEAR(lanes.axis.norm(), 1, kReferenceTolerance);
  const double half_angle_off = std::abs(HalfAngle(lanes) - HalfAngle(exact));
  const double axis_off = AngleBetween(lanes.axis, exact.axis);
  EXPECT_LE(half_angle_off, kLanesTolerance);
  EXPECT_LE(axis_off, kLanesTolerance);
  agreement->half_angle = std::max(agreement->half_angle, half_angle_off);
  agreement->axis = std::max(agreement->axis, axis_off);
  // Both cones, and so every direction of the union by angles, lie in each union: within the
  // rounding for the union by angles, within kLanesTolerance for the lanes (they promise no
  // margin: the patches' cones below carry it, kConeRounding).
  for (const NormalCone& cone : {pair.a, pair.b, exact}) {
    for (int k = 0; k < kRimPoints; ++k) {
      const Point rim = Rim(cone, 2 * M_PI * k / kRimPoints);
      if (&cone != &exact) {
        EXPECT_LE(AngleBetween(rim, exact.axis), HalfAngle(exact) + kReferenceTolerance);
      }
      EXPECT_LE(AngleBetween(rim, lanes.axis), HalfAngle(lanes) + kLanesTolerance);
    }
  }
}

// Every pair in every lane: the pairs go through ConeLanes::Union kLanes at a time, shifted by
// 0 to kLanes - 1 places; lanes past the last pair stay open cones.
TEST(NormalCone, TheLanesAgreeWithTheUnionByAnglesOnRandomAndAdversarialCones) {
  const std::vector<ConePair> pairs = RandomAndAdversarialPairs();
  Agreement agreement;
  for (int shift = 0; shift < ConeLanes::kLanes; ++shift) {
    std::vector<ConePair> shifted(shift, pairs.back());
    shifted.insert(shifted.end(), pairs.begin(), pairs.end());
    for (size_t first = 0; first < shifted.size(); first += ConeLanes::kLanes) {
      const int count = int(std::min<size_t>(ConeLanes::kLanes, shifted.size() - first));
      ConeLanes a, b;
      for (int lane = 0; lane < count; ++lane) {
        a.Set(lane, shifted[first + lane].a);
        b.Set(lane, shifted[first + lane].b);
      }
      const ConeLanes both = ConeLanes::Union(a, b);
      for (int lane = 0; lane < count; ++lane)
        ExpectAgree(shifted[first + lane], both.Cone(lane), &agreement);
      for (int lane = count; lane < ConeLanes::kLanes; ++lane) EXPECT_FALSE(both.Cone(lane).Narrow());
    }
  }
  // Every case of the union was reached.
  EXPECT_GT(agreement.joined, 1000);
  EXPECT_GT(agreement.held, 1000);
  EXPECT_GT(agreement.open, 1000);
  std::printf(
      "%zu pairs, each in every lane: %d joined, %d held, %d open, %d at 90 degrees; the lanes off by at "
      "most %.2g rad on the half-angle, %.2g rad on the axis\n",
      pairs.size(), agreement.joined, agreement.held, agreement.open, agreement.at_right_angle,
      agreement.half_angle, agreement.axis);
}

}  // namespace
}  // namespace flagsim::sim
