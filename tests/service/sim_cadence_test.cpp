#include "server/service/sim_cadence.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace flagsim {
namespace {

/// The step times (step k at k * dt, k = 0 .. steps - 1) at which the cadence falls due.
std::vector<int> DueSteps(double rate, double dt, int steps, double tolerance) {
  SimCadence cadence;
  std::vector<int> due;
  double time = 0;
  for (int k = 0; k < steps; ++k) {
    if (cadence.Due(time, rate, tolerance)) due.push_back(k);
    time += dt;  // accumulated, with its rounding, as a simulation's clock is
  }
  return due;
}

TEST(SimCadence, DueAtZeroThenEveryPeriod) {
  const std::vector<int> due = DueSteps(10, 0.002, 500, 0.001);
  ASSERT_EQ(due.size(), 10u);
  for (size_t i = 0; i < due.size(); ++i) EXPECT_EQ(due[i], int(50 * i));
}

TEST(SimCadence, WithoutToleranceARoundingErrorCanCostAStep) {
  // 0.1 is not a sum of 0.002s in floating point: some periods fall a step late
  const std::vector<int> strict = DueSteps(10, 0.002, 500, 0);
  ASSERT_EQ(strict.size(), 10u);
  for (size_t i = 0; i < strict.size(); ++i) EXPECT_LE(strict[i] - int(50 * i), 1);
}

TEST(SimCadence, NotUntilDueAndNeverAtRateZero) {
  SimCadence cadence;
  EXPECT_FALSE(cadence.Due(0, 0));
  EXPECT_TRUE(cadence.Due(0, 30));
  EXPECT_FALSE(cadence.Due(0.02, 30));
  EXPECT_NEAR(cadence.next(), 1.0 / 30, 1e-15);
}

TEST(SimCadence, ALateCheckDoesNotOweEveryPeriodMissed) {
  SimCadence cadence;
  EXPECT_TRUE(cadence.Due(0, 10));
  EXPECT_TRUE(cadence.Due(0.55, 10));  // five periods missed
  EXPECT_TRUE(cadence.Due(0.56, 10));  // one more at the next check, not four
  EXPECT_FALSE(cadence.Due(0.57, 10));
  EXPECT_FALSE(cadence.Due(0.60, 10));
  EXPECT_TRUE(cadence.Due(0.70, 10));  // on schedule from there: 0.65, 0.75, ...
  EXPECT_NEAR(cadence.next(), 0.75, 1e-12);
}

}  // namespace
}  // namespace flagsim
