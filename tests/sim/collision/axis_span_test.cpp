// Spans along an axis: what a set of points or balls covers, and when two are apart.
#include "server/sim/collision/axis_span.hpp"

#include <gtest/gtest.h>

namespace flagsim::sim {
namespace {

TEST(AxisSpan, PointsAndBallsCoverFromTheLeastToTheMost) {
  AxisSpan points;
  for (double along : {0.5, -1.0, 2.0}) points.Add(along);
  EXPECT_EQ(points.least, -1.0);
  EXPECT_EQ(points.most, 2.0);
  AxisSpan balls;
  balls.Add(0.0, 0.25);
  balls.Add(1.0, 0.5);
  EXPECT_EQ(balls.least, -0.25);
  EXPECT_EQ(balls.most, 1.5);
}

// Beyond looks one way along the axis; Apart both ways. A gap of exactly the room is not enough.
TEST(AxisSpan, BeyondIsOneSidedAndApartIsEither) {
  AxisSpan low, high;
  low.Add(0.0);
  low.Add(1.0);
  high.Add(1.5);
  high.Add(3.0);
  EXPECT_TRUE(high.Beyond(low, 0.25));
  EXPECT_FALSE(low.Beyond(high, 0.25));
  EXPECT_TRUE(Apart(low, high, 0.25));
  EXPECT_TRUE(Apart(high, low, 0.25));
  EXPECT_FALSE(Apart(low, high, 0.5));
  EXPECT_FALSE(Apart(low, high, 1.0));
  AxisSpan overlapping;
  overlapping.Add(0.5, 1.0);  // from -0.5 to 1.5: reaches into low, touches high
  EXPECT_FALSE(Apart(low, overlapping, 0.0));
  EXPECT_FALSE(Apart(overlapping, high, 0.0));
}

}  // namespace
}  // namespace flagsim::sim
