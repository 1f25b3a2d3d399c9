#include "server/sim/control_laws.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace flagsim::sim {
namespace {

// Keys at t = 1 (value 2) and t = 3 (value 6); neighbours at t = 0 (value 0) and t = 4 (value 10).
Segment Keys() { return Segment{1, 3, 2, 6, 0, 0, 4, 10}; }

TEST(ControlLaws, EveryLawIsExactAtItsKeys) {
  for (const ControlLaw law :
       {ControlLaw::kStep, ControlLaw::kLinear, ControlLaw::kSmooth, ControlLaw::kCubic}) {
    EXPECT_DOUBLE_EQ(Interpolate(law, Keys(), 3.0), 6.0) << ControlLawNames()[int(law)];
    if (law != ControlLaw::kStep) {
      EXPECT_DOUBLE_EQ(Interpolate(law, Keys(), 1.0), 2.0);
    }
  }
  EXPECT_DOUBLE_EQ(Interpolate(ControlLaw::kStep, Keys(), 1.0), 2.0);
}

TEST(ControlLaws, ValuesAtKnownPoints) {
  // step: the first key's value until the next key
  EXPECT_DOUBLE_EQ(Interpolate(ControlLaw::kStep, Keys(), 2.999), 2.0);
  // linear: a quarter of the way, 2 + 4/4
  EXPECT_DOUBLE_EQ(Interpolate(ControlLaw::kLinear, Keys(), 1.5), 3.0);
  // smooth at s = 1/4: 3/16 - 2/64 = 0.15625 of the way
  EXPECT_DOUBLE_EQ(Interpolate(ControlLaw::kSmooth, Keys(), 1.5), 2.0 + 4.0 * 0.15625);
  EXPECT_DOUBLE_EQ(Interpolate(ControlLaw::kSmooth, Keys(), 2.0), 4.0);  // symmetric: halfway
  // cubic: rates (6 - 0) / 3 = 2 at t = 1 and (10 - 2) / 3 = 8/3 at t = 3, times the span 2:
  // m0 = 4, m1 = 16/3; at s = 1/2 the Hermite value is (v0 + v1) / 2 + (m0 - m1) / 8.
  EXPECT_NEAR(Interpolate(ControlLaw::kCubic, Keys(), 2.0), 4.0 + (4.0 - 16.0 / 3.0) / 8.0, 1e-12);
}

// Keys a denormal's breadth apart (a KEYFRAME command may put them there): the cubic's rates
// would be infinite, and its value NaN; scaled by the span first, they stay finite, and so does
// every law's value and range.
TEST(ControlLaws, KeysAlmostTogetherGiveFiniteValues) {
  const Segment close{0, 1.7e-307, 1500, 2500, 0, 1500, 1.7e-307, 2500};
  for (const ControlLaw law :
       {ControlLaw::kStep, ControlLaw::kLinear, ControlLaw::kSmooth, ControlLaw::kCubic}) {
    for (const double t : {0.0, 1e-307, 1.7e-307, 1.0}) {
      const double value = Interpolate(law, close, t);
      EXPECT_TRUE(value >= 1500 && value <= 2500)
          << ControlLawNames()[int(law)] << " at " << t << ": " << value;
    }
    const ValueRange range = RangeOver(law, close);
    EXPECT_TRUE(std::isfinite(range.low) && std::isfinite(range.high)) << ControlLawNames()[int(law)];
  }
}

// The rate of change, by central differences, just inside the segment at each end.
double RateAt(ControlLaw law, const Segment& segment, double t) {
  const double h = 1e-6;
  return (Interpolate(law, segment, t + h) - Interpolate(law, segment, t - h)) / (2 * h);
}

TEST(ControlLaws, SmoothStartsAndEndsAtRest) {
  EXPECT_NEAR(RateAt(ControlLaw::kSmooth, Keys(), 1.0 + 1e-5), 0.0, 1e-3);
  EXPECT_NEAR(RateAt(ControlLaw::kSmooth, Keys(), 3.0 - 1e-5), 0.0, 1e-3);
}

TEST(ControlLaws, CubicHasTheSameRateOnBothSidesOfAKey) {
  // Keys at 0, 1, 3, 4 with values 0, 2, 6, 10 (and 12 at 6): the segment (1, 3) and the next
  // one (3, 4) meet at t = 3 with equal rates.
  const Segment before{1, 3, 2, 6, 0, 0, 4, 10};
  const Segment after{3, 4, 6, 10, 1, 2, 6, 12};
  EXPECT_NEAR(RateAt(ControlLaw::kCubic, before, 3.0 - 1e-5), RateAt(ControlLaw::kCubic, after, 3.0 + 1e-5),
              1e-3);
  EXPECT_NEAR(RateAt(ControlLaw::kCubic, before, 3.0 - 1e-5), 8.0 / 3.0, 1e-3);
}

TEST(ControlLaws, LinearAndCubicAreContinuousInside) {
  for (const ControlLaw law : {ControlLaw::kLinear, ControlLaw::kSmooth, ControlLaw::kCubic}) {
    for (double t = 1.0; t < 3.0; t += 0.01) {
      EXPECT_LT(std::abs(Interpolate(law, Keys(), t + 1e-7) - Interpolate(law, Keys(), t)), 1e-5);
    }
  }
}

TEST(ControlLaws, RangesHoldEveryValueOfTheSegment) {
  // Keys 0 at t = 0, 1 at t = 1 and 2, 0 at t = 3: the cubic on (1, 2) has rates +1/2 and -1/2
  // at its ends and rises above 1 between them; the other laws stay between the keys.
  const Segment peak{1, 2, 1, 1, 0, 0, 3, 0};
  for (const ControlLaw law :
       {ControlLaw::kStep, ControlLaw::kLinear, ControlLaw::kSmooth, ControlLaw::kCubic}) {
    const ValueRange range = RangeOver(law, peak);
    double high = -1;
    for (double t = 1; t <= 2; t += 1e-3) {
      const double value = Interpolate(law, peak, t);
      EXPECT_GE(value, range.low);
      EXPECT_LE(value, range.high);
      high = std::max(high, value);
    }
    if (law == ControlLaw::kCubic) {
      EXPECT_GT(high, 1.1);  // the overshoot: (v0 + v1) / 2 + (m0 - m1) / 8 = 1.125 at s = 1/2
    } else {
      EXPECT_EQ(range.high, 1.0);
    }
  }
  EXPECT_EQ(RangeOver(ControlLaw::kLinear, Keys()).low, 2.0);
  EXPECT_EQ(RangeOver(ControlLaw::kLinear, Keys()).high, 6.0);
}

TEST(ControlLaws, WindTurnsByAngleAndKeepsUnitLength) {
  const std::array<double, 3> east{1, 0, 0}, north{0, 0, -1}, west{-1, 0, 0};
  const auto half = Slerp(east, north, 0.5);
  EXPECT_NEAR(half[0], std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(half[2], -std::sqrt(0.5), 1e-12);
  // Opposite: through the horizontal plane, a quarter turn halfway, never through zero.
  const auto across = Slerp(east, west, 0.5);
  EXPECT_NEAR(std::abs(across[2]), 1.0, 1e-12);
  EXPECT_NEAR(across[1], 0.0, 1e-12);
  const auto end = Slerp(east, west, 1.0);
  EXPECT_NEAR(end[0], -1.0, 1e-12);
  for (double s = 0; s <= 1; s += 0.1) {
    const auto v = Slerp(east, north, s);
    EXPECT_NEAR(v[0] * v[0] + v[1] * v[1] + v[2] * v[2], 1.0, 1e-12);
  }
}

}  // namespace
}  // namespace flagsim::sim
