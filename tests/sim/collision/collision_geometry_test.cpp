// Closest points and first contacts of a point and a triangle, and of two edges.
#include "server/sim/collision/collision_geometry.hpp"

#include <gtest/gtest.h>

#include <optional>

namespace flagsim::sim {
namespace {

TEST(CollisionGeometry, ClosestPointsOnATriangleAndTwoSegments) {
  const Point a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0};
  EXPECT_TRUE(ClosestOnTriangle({0.25, 0.25, 1}, a, b, c).isApprox(Eigen::Vector3d(0.5, 0.25, 0.25)));
  EXPECT_TRUE(ClosestOnTriangle({2, -1, 0}, a, b, c).isApprox(Eigen::Vector3d(0, 1, 0)));
  EXPECT_TRUE(ClosestOnTriangle({1, 1, 0}, a, b, c).isApprox(Eigen::Vector3d(0, 0.5, 0.5)));
  const SegmentParameters crossing = ClosestOnSegments({0, 0, 0}, {2, 0, 0}, {0.5, -1, 1}, {0.5, 1, 1});
  EXPECT_DOUBLE_EQ(crossing.s, 0.25);
  EXPECT_DOUBLE_EQ(crossing.t, 0.5);
}

TEST(CollisionGeometry, APointThroughATriangleMeetsItWhenItReachesThePlane) {
  const Point a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0};
  const Primitives through{{Point{0.2, 0.2, 0.3}, a, b, c}, {Point{0.2, 0.2, -0.1}, a, b, c}};
  const std::optional<double> when = PointTriangleContact(through, 1e-6);
  ASSERT_TRUE(when.has_value());
  EXPECT_NEAR(*when, 0.75, 1e-9);
  const Primitives beside{{Point{1.2, 1.2, 0.3}, a, b, c}, {Point{1.2, 1.2, -0.1}, a, b, c}};
  EXPECT_FALSE(PointTriangleContact(beside, 1e-6).has_value());
}

TEST(CollisionGeometry, TwoEdgesThatPassThroughEachOtherMeet) {
  // One edge along x at z = 0.2 falls to z = -0.2 through a fixed edge along y.
  const Primitives through{{Point{-1, 0, 0.2}, Point{1, 0, 0.2}, Point{0, -1, 0}, Point{0, 1, 0}},
                           {Point{-1, 0, -0.2}, Point{1, 0, -0.2}, Point{0, -1, 0}, Point{0, 1, 0}}};
  const std::optional<double> when = EdgeEdgeContact(through, 1e-6);
  ASSERT_TRUE(when.has_value());
  EXPECT_NEAR(*when, 0.5, 1e-9);
  Primitives apart = through;
  for (Point& p : apart.start) p.x() += p.y() == 0 ? 5 : 0;  // the moving edge shifted clear
  for (Point& p : apart.end) p.x() += p.y() == 0 ? 5 : 0;
  EXPECT_FALSE(EdgeEdgeContact(apart, 1e-6).has_value());
}

}  // namespace
}  // namespace flagsim::sim
