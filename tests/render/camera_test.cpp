#include "render/camera.hpp"

#include <gtest/gtest.h>

namespace flagsim::render {
namespace {

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

}  // namespace
}  // namespace flagsim::render
