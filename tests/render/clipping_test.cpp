#include "server/render/clipping.hpp"

#include <gtest/gtest.h>

namespace flagsim::render {
namespace {

ClipVertex V(float x, float y, float z, float w, float channel = 0) {
  ClipVertex v;
  v.clip = Eigen::Vector4f(x, y, z, w);
  v.channels[0] = channel;
  return v;
}

TEST(Clipping, ClassifiesInsideOutsideAndCrossing) {
  EXPECT_EQ(ClassifyTriangle(V(0, 0, 0, 1), V(0.5f, 0, 0, 1), V(0, 0.5f, 0, 1)), ClipTest::kInside);
  // all three behind the near plane (z < -w)
  EXPECT_EQ(ClassifyTriangle(V(0, 0, -3, 1), V(1, 0, -3, 1), V(0, 1, -3, 1)), ClipTest::kOutside);
  // all right of the view (x > w), even though inside the guard band
  EXPECT_EQ(ClassifyTriangle(V(2, 0, 0, 1), V(3, 0, 0, 1), V(2, 1, 0, 1)), ClipTest::kOutside);
  // one vertex behind the near plane
  EXPECT_EQ(ClassifyTriangle(V(0, 0, 0, 1), V(0.5f, 0, 0, 1), V(0, 0.5f, -2, 1)), ClipTest::kCrossing);
  // past the screen's edge but inside the guard band: no clipping needed
  EXPECT_EQ(ClassifyTriangle(V(0, 0, 0, 1), V(3, 0, 0, 1), V(0, 3, 0, 1)), ClipTest::kInside);
}

TEST(Clipping, NearPlaneCutKeepsTheFrontPartAndInterpolates) {
  // Vertex c is behind the near plane; the cut lands where z = -w on edges a-c and b-c.
  const ClipVertex a = V(-0.5f, 0, 0, 1, 0), b = V(0.5f, 0, 0, 1, 0), c = V(0, 0.5f, -3, 1, 3);
  std::vector<ClipVertex> out;
  ClipTriangle(a, b, c, &out);
  ASSERT_EQ(out.size(), 6u);  // a quadrilateral, as two triangles
  for (const ClipVertex& v : out) {
    EXPECT_GE(v.clip.z() + v.clip.w(), -1e-6f);
    // the channel rides along the edge: 0 at z = 0, 3 at z = -3, so it equals -z
    EXPECT_NEAR(v.channels[0], -v.clip.z(), 1e-5f);
  }
}

TEST(Clipping, ASharedEdgeIsCutAtTheSamePointFromBothSides) {
  // Triangles (a, b, c) and (b, a, d) share edge a-b, which crosses the near plane.
  const ClipVertex a = V(0, 0, 0.5f, 1), b = V(0.3f, 0.2f, -2.5f, 1), c = V(-0.4f, 0.3f, 0.2f, 1),
                   d = V(0.4f, -0.3f, 0.1f, 1);
  std::vector<ClipVertex> first, second;
  ClipTriangle(a, b, c, &first);
  ClipTriangle(b, a, d, &second);
  int shared = 0;
  for (const ClipVertex& p : first) {
    if (std::abs(p.clip.z() + p.clip.w()) > 1e-6f) continue;        // only points on the near plane
    for (const ClipVertex& q : second) shared += p.clip == q.clip;  // bit for bit
  }
  EXPECT_GT(shared, 0);
}

TEST(Clipping, LinesAreCutToTheVolume) {
  Eigen::Vector4f a(0, 0, 0, 1), b(0, 0, -5, 1);  // b far behind the near plane
  ASSERT_TRUE(ClipLine(&a, &b));
  EXPECT_NEAR(b.z(), -1.0f, 1e-6f);
  Eigen::Vector4f c(0, 0, -3, 1), d(0, 0, -5, 1);
  EXPECT_FALSE(ClipLine(&c, &d));
}

}  // namespace
}  // namespace flagsim::render
