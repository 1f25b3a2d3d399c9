// The camera moves that know where the flag is: frame it, zoom toward what a pixel shows, and
// never through the flag's near side.
#include "server/render/camera_on_flag.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

namespace flagsim::render {
namespace {

/// A flat 1.5 m x 1 m flag in the plane z = 0, hoist at x = 0, top at y = 2.5.
FlagSurface FlatFlag(int cols = 16, int rows = 12) {
  FlagSurface flag{{}, cols, rows};
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) flag.nodes.emplace_back(1.5 * c / (cols - 1), 2.5 - 1.0 * r / (rows - 1), 0.0);
  }
  return flag;
}

/// Looking at the flag's middle square-on from `distance` m in front of it.
Camera FacingFlag(double distance) {
  Camera camera;
  camera.target = {0.75, 2.0, 0.0};
  camera.eye = camera.target + Eigen::Vector3d(0, 0, distance);
  return camera;
}

CameraMove Move(int operation, double factor = 1, Eigen::Vector3d vector = Eigen::Vector3d::Zero()) {
  CameraMove move;
  move.operation = operation;
  move.factor = factor;
  move.vector = vector;
  return move;
}

// The target 2 m behind the flag: a zoom toward it would pass through the flag (as 30 clicks of
// the wheel used to, to sky and ground) but stops kFlagClearance in front of it.
TEST(CameraOnFlag, ZoomStopsShortOfTheFlagHoweverOftenItIsAskedFor) {
  const FlagSurface flag = FlatFlag();
  for (const int operation : {CameraMove::kZoom, CameraMove::kZoomAt}) {
    Camera camera = FacingFlag(5);
    camera.target.z() = -2;
    camera.eye.z() = 5;
    for (int notch = 0; notch < 40; ++notch) {
      ASSERT_EQ(ApplyFlagCameraMove(Move(operation, 1.5, {640, 360, 0}), flag, &camera), "") << "notch " << notch;
    }
    EXPECT_GE(camera.eye.z(), kFlagClearance - 1e-9) << "still in front of the flag, not through it";
    // At the flag (zoom), or where the eye-target distance reaches Camera::kMinZoomDistance
    // (zoom at: the target comes toward the flag too, 7 m / 70 of eye-target distance).
    EXPECT_LE(camera.eye.z(), operation == CameraMove::kZoom ? kFlagClearance + 1e-9 : 5.0 / 70 + 1e-9)
        << "and as near as it may go";
  }
}

TEST(CameraOnFlag, ZoomAtKeepsThePointUnderThePixel) {
  const FlagSurface flag = FlatFlag();
  Camera camera = FacingFlag(5);
  const double px = 700, py = 300;
  const std::optional<Eigen::Vector3d> before = FlagUnderPixel(camera, flag, px, py);
  ASSERT_TRUE(before.has_value()) << "the pixel shows the flag";
  const double distance = (*before - camera.eye).norm();
  ASSERT_EQ(ApplyFlagCameraMove(Move(CameraMove::kZoomAt, 2, {px, py, 0}), flag, &camera), "");
  const std::optional<Eigen::Vector3d> after = FlagUnderPixel(camera, flag, px, py);
  ASSERT_TRUE(after.has_value());
  EXPECT_LT((*after - *before).norm(), 1e-9) << "the same point of the flag under the pixel";
  EXPECT_NEAR((*after - camera.eye).norm(), distance / 2, 1e-9);
}

TEST(CameraOnFlag, ZoomAtOverTheSkyGoesTowardTheTargetsDepth) {
  const FlagSurface flag = FlatFlag();
  Camera camera = FacingFlag(5);
  ASSERT_FALSE(FlagUnderPixel(camera, flag, 10, 10).has_value()) << "a corner shows sky";
  ASSERT_EQ(ApplyFlagCameraMove(Move(CameraMove::kZoomAt, 2, {10, 10, 0}), flag, &camera), "");
  EXPECT_NEAR(camera.eye.z(), 2.5, 1e-9) << "half way to the target's depth";
  // Many more: the eye stops the flag's size (half its 1.8 m diagonal) from the point in the air,
  // where the flag is still in view, instead of closing in on empty sky.
  for (int notch = 0; notch < 40; ++notch) {
    ASSERT_EQ(ApplyFlagCameraMove(Move(CameraMove::kZoomAt, 1.5, {10, 10, 0}), flag, &camera), "");
  }
  // (0.85 m along the slanting ray through the corner pixel: 0.73 m in front of the flag's plane.)
  EXPECT_GT(camera.eye.z(), 0.7);
}

TEST(CameraOnFlag, FrameCentresTheFlagAndFitsItInThePicture) {
  const FlagSurface flag = FlatFlag();
  Camera camera;
  camera.eye = {9, 6, 30};  // far off and to the side
  camera.target = {3, 1, 0};
  const Eigen::Vector3d sight = (camera.target - camera.eye).normalized();
  ASSERT_EQ(ApplyFlagCameraMove(Move(CameraMove::kFrame), flag, &camera), "");
  EXPECT_LT((camera.target - Eigen::Vector3d(0.75, 2.0, 0.0)).norm(), 1e-9) << "aimed at the flag's centre";
  EXPECT_LT((camera.target - camera.eye).normalized().cross(sight).norm(), 1e-9) << "along the same line of sight";
  const Eigen::Matrix4d clip_from_world = camera.Projection() * camera.View();
  double low_x = 1e9, high_x = -1e9, low_y = 1e9, high_y = -1e9;
  for (const Eigen::Vector3d& node : flag.nodes) {
    Eigen::Vector2d pixel;
    ASSERT_TRUE(ToPixel(clip_from_world, camera, node.x(), node.y(), node.z(), &pixel));
    low_x = std::min(low_x, pixel.x()), high_x = std::max(high_x, pixel.x());
    low_y = std::min(low_y, pixel.y()), high_y = std::max(high_y, pixel.y());
  }
  EXPECT_GE(low_x, 0);
  EXPECT_LE(high_x, camera.width);
  EXPECT_GE(low_y, 0);
  EXPECT_LE(high_y, camera.height);
  EXPECT_GT(high_y - low_y, 0.4 * camera.height) << "big enough to see: the flag fills much of the picture";
}

TEST(CameraOnFlag, APixelOutsideThePictureIsRefusedAndChangesNothing) {
  const FlagSurface flag = FlatFlag();
  Camera camera = FacingFlag(5);
  const Camera before = camera;
  const std::string problem = ApplyFlagCameraMove(Move(CameraMove::kZoomAt, 2, {1281, 10, 0}), flag, &camera);
  EXPECT_NE(problem.find("outside the 1280 x 720 px picture"), std::string::npos) << problem;
  EXPECT_EQ(camera.eye, before.eye);
  EXPECT_EQ(camera.target, before.target);
}

}  // namespace
}  // namespace flagsim::render
