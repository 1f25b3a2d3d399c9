#include "server/render/camera.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace flagsim::render {
namespace {

/// rad: the azimuth and elevation of the eye about the target, as Orbit measures them.
double Azimuth(const Camera& camera) {
  const Eigen::Vector3d arm = camera.eye - camera.target;
  return std::atan2(arm.x(), arm.z());
}
double Elevation(const Camera& camera) {
  const Eigen::Vector3d arm = camera.eye - camera.target;
  return std::asin(arm.y() / arm.norm());
}

/// The camera with its eye at (azimuth, elevation) about the target, the ground ignored.
Camera PlacedAt(Camera camera, double azimuth, double elevation) {
  const double radius = (camera.eye - camera.target).norm();
  camera.eye =
      camera.target + radius * Eigen::Vector3d(std::cos(elevation) * std::sin(azimuth), std::sin(elevation),
                                               std::cos(elevation) * std::cos(azimuth));
  return camera;
}

Eigen::Vector3d ToCamera(const Camera& camera, const Eigen::Vector3d& p) {
  return (camera.View() * p.homogeneous()).head<3>();
}

TEST(Camera, LooksDownMinusZAtTheTarget) {
  const Camera camera;
  EXPECT_NEAR(ToCamera(camera, camera.eye).norm(), 0, 1e-12);
  const Eigen::Vector3d target = ToCamera(camera, camera.target);
  EXPECT_NEAR(target.x(), 0, 1e-12);
  EXPECT_NEAR(target.y(), 0, 1e-12);
  EXPECT_NEAR(target.z(), -(camera.target - camera.eye).norm(), 1e-12);
}

TEST(Camera, ProjectionMapsNearAndFarToTheDepthRange) {
  const Camera camera;
  const auto ndc_z = [&](double distance) {
    const Eigen::Vector4d clip = camera.Projection() * Eigen::Vector4d(0, 0, -distance, 1);
    return clip.z() / clip.w();
  };
  EXPECT_NEAR(ndc_z(camera.near_plane), -1, 1e-9);
  EXPECT_NEAR(ndc_z(camera.far_plane), 1, 1e-9);
}

TEST(Camera, RotatingTheSceneTurnsAboutTheTarget) {
  Camera camera;
  const Eigen::Vector3d before = ToCamera(camera, camera.target);
  camera.RotateScene(Eigen::Vector3d::UnitY(), 0.7);
  EXPECT_NEAR((ToCamera(camera, camera.target) - before).norm(), 0, 1e-12);
  // a point one metre right of the target moves on a circle around it
  const Eigen::Vector3d moved = camera.scene * (camera.target + Eigen::Vector3d::UnitX());
  EXPECT_NEAR((moved - camera.target).norm(), 1, 1e-12);
  EXPECT_NEAR(moved.y(), camera.target.y(), 1e-12);
}

TEST(Camera, ScalingAboutAPointKeepsItFixed) {
  Camera camera;
  const Eigen::Vector3d centre(1, 2, 0);
  camera.ScaleScene(2.0, centre);
  EXPECT_NEAR((camera.scene * centre - centre).norm(), 0, 1e-12);
  EXPECT_NEAR((camera.scene * (centre + Eigen::Vector3d(0.5, 0, 0)) - centre).norm(), 1.0, 1e-12);
  EXPECT_NEAR((camera.EyeInWorld() - (centre + (camera.eye - centre) / 2)).norm(), 0, 1e-12);
}

TEST(Camera, OrbitKeepsTheDistanceAndTranslateMovesBoth) {
  Camera camera;
  const double distance = (camera.eye - camera.target).norm();
  camera.Orbit(0.5, 0.2);
  EXPECT_NEAR((camera.eye - camera.target).norm(), distance, 1e-12);
  const Eigen::Vector3d target = camera.target;
  camera.Translate(Eigen::Vector3d(1, 0, 0));
  EXPECT_NEAR((camera.target - target - Eigen::Vector3d(1, 0, 0)).norm(), 0, 1e-12);
}

TEST(Camera, ZoomDividesTheDistanceAndKeepsTheDirection) {
  for (const double factor : {2.0, 0.8, 1.0}) {
    Camera camera;
    const Eigen::Vector3d arm = camera.eye - camera.target;
    camera.Zoom(factor);
    const Eigen::Vector3d zoomed = camera.eye - camera.target;
    EXPECT_NEAR(zoomed.norm(), arm.norm() / factor, 1e-12) << factor;
    EXPECT_NEAR((zoomed.normalized() - arm.normalized()).norm(), 0, 1e-12) << factor;
    EXPECT_EQ(camera.target, Camera{}.target);
  }
}

TEST(Camera, ZoomKeepsTheDistanceWithinItsRange) {
  Camera level;  // looking horizontally, so the ground is out of the way
  level.eye = level.target + Eigen::Vector3d(0, 0, 5);
  Camera near = level, far = level;
  near.Zoom(100);  // 0.05 m wanted
  EXPECT_NEAR((near.eye - near.target).norm(), Camera::kMinZoomDistance, 1e-12);
  far.Zoom(0.01);  // 500 m wanted
  EXPECT_NEAR((far.eye - far.target).norm(), Camera::kMaxZoomDistance, 1e-9);
  EXPECT_NEAR(far.eye.y(), level.eye.y(), 1e-12);
  // From beyond the range a zoom out does not bring the eye nearer.
  Camera beyond = level;
  beyond.eye = beyond.target + Eigen::Vector3d(0, 0, 1.5 * Camera::kMaxZoomDistance);
  const Eigen::Vector3d eye = beyond.eye;
  beyond.Zoom(0.5);
  EXPECT_NEAR((beyond.eye - eye).norm(), 0, 1e-9);
}

TEST(Camera, ZoomingOutStopsTheEyeAtTheGround) {
  Camera camera;  // looking down a little at the flag: backing away lowers the eye
  const Eigen::Vector3d direction = (camera.eye - camera.target).normalized();
  ASSERT_LT(direction.y(), 0);
  ASSERT_LT(camera.target.y() + Camera::kMaxZoomDistance * direction.y(), 0);
  camera.Zoom(0.01);
  EXPECT_NEAR(camera.EyeHeight(), Camera::kMinEyeHeight, 1e-9);
  EXPECT_NEAR((camera.eye - camera.target).norm(),
              (Camera::kMinEyeHeight - camera.target.y()) / direction.y(), 1e-9);
  EXPECT_NEAR(((camera.eye - camera.target).normalized() - direction).norm(), 0, 1e-12);
}

TEST(Camera, OrbitingDownStopsAtTheGround) {
  Camera camera;
  const double radius = (camera.eye - camera.target).norm(), azimuth = Azimuth(camera);
  const double elevation = Elevation(camera), down = -60 * M_PI / 180;
  ASSERT_LT(PlacedAt(camera, azimuth, elevation + down).EyeHeight(), Camera::kMinEyeHeight);
  camera.Orbit(0, down);
  EXPECT_NEAR(camera.eye.y(), Camera::kMinEyeHeight, 1e-9);
  EXPECT_GE(camera.eye.y(), Camera::kMinEyeHeight - 1e-12);
  EXPECT_NEAR((camera.eye - camera.target).norm(), radius, 1e-12);
  EXPECT_NEAR(Azimuth(camera), azimuth, 1e-12);
  // The elevation at which the eye is at the least height: target.y + r sin(phi) = kMinEyeHeight.
  EXPECT_NEAR(Elevation(camera), std::asin((Camera::kMinEyeHeight - camera.target.y()) / radius), 1e-9);
  // Up again, it goes the whole way.
  const double at_ground = Elevation(camera);
  camera.Orbit(0.3, 0.4);
  EXPECT_NEAR(Elevation(camera), at_ground + 0.4, 1e-12);
  EXPECT_NEAR(std::remainder(Azimuth(camera) - azimuth - 0.3, 2 * M_PI), 0, 1e-12);
}

TEST(Camera, OrbitingDownStopsAtTheGroundOfATurnedAndScaledScene) {
  Camera camera;
  camera.RotateScene(Eigen::Vector3d::UnitX(), -0.35);
  camera.ScaleScene(1.3, Eigen::Vector3d(0.5, 1.0, 0.2));
  ASSERT_GT(camera.EyeHeight(), Camera::kMinEyeHeight);
  const double radius = (camera.eye - camera.target).norm(), azimuth = Azimuth(camera) + 0.4;
  const double from = Elevation(camera), down = -1.2;
  ASSERT_LT(PlacedAt(camera, azimuth, from + down).EyeHeight(), Camera::kMinEyeHeight);
  Camera orbited = camera;
  orbited.Orbit(0.4, down);
  EXPECT_NEAR(orbited.EyeHeight(), Camera::kMinEyeHeight, 1e-9);
  EXPECT_GE(orbited.EyeHeight(), Camera::kMinEyeHeight - 1e-12);
  EXPECT_NEAR((orbited.eye - orbited.target).norm(), radius, 1e-12);
  EXPECT_NEAR(Azimuth(orbited), azimuth, 1e-12);
  // It stopped where it first met the ground: above it all the way there.
  const double to = Elevation(orbited);
  EXPECT_LT(to, from);
  for (int i = 0; i <= 100; ++i) {
    const double elevation = from + (to - from) * i / 100;
    EXPECT_GE(PlacedAt(camera, azimuth, elevation).EyeHeight(), Camera::kMinEyeHeight - 1e-9) << elevation;
  }
}

TEST(Camera, OrbitStopsWhereTheEyeFirstMeetsTheGroundThoughItWouldComeUpAgain) {
  // The world turned a quarter about x: at azimuth 0 the eye's height is target.y - r cos(phi),
  // above the ground at elevations of +-1.2 rad and under it at 0.
  Camera camera;
  camera.RotateScene(Eigen::Vector3d::UnitX(), -M_PI / 2);
  camera = PlacedAt(camera, 0, -1.2);
  const double radius = (camera.eye - camera.target).norm();
  ASSERT_GT(camera.EyeHeight(), Camera::kMinEyeHeight);
  ASSERT_GT(PlacedAt(camera, 0, 1.2).EyeHeight(), Camera::kMinEyeHeight);
  ASSERT_LT(PlacedAt(camera, 0, 0).EyeHeight(), 0);
  camera.Orbit(0, 2.4);
  EXPECT_NEAR(camera.EyeHeight(), Camera::kMinEyeHeight, 1e-9);
  EXPECT_NEAR(Elevation(camera), -std::acos((camera.target.y() - Camera::kMinEyeHeight) / radius), 1e-9);
}

TEST(Camera, AnEyeUnderTheGroundMayRiseButNotSink) {
  Camera camera;
  camera.eye = Eigen::Vector3d(0.8, -1, 4);  // as a scene file might put it
  const double height = camera.EyeHeight();
  Camera sunk = camera;
  sunk.Orbit(0, -0.5);
  EXPECT_NEAR(sunk.EyeHeight(), height, 1e-9);
  Camera risen = camera;
  risen.Orbit(0, 0.5);
  EXPECT_GT(risen.EyeHeight(), height + 0.1);
}

}  // namespace
}  // namespace flagsim::render
