#include "server/render/camera_moves.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace flagsim::render {
namespace {

const double kNan = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

TEST(CameraMoves, BadFieldsAreRejectedByNameAndChangeNothing) {
  struct Case {
    CameraMove move;
    const char* field;
  };
  const auto move = [](int operation) {
    CameraMove m;
    m.operation = operation;
    return m;
  };
  std::vector<Case> cases;
  for (const int op :
       {CameraMove::kRotateX, CameraMove::kRotateY, CameraMove::kRotateZ, CameraMove::kOrbit}) {
    for (const double bad : {kNan, kInf, -kInf, 7.0, -100.0}) {
      CameraMove m = move(op);
      m.angle = bad;
      cases.push_back({m, "angle:"});
    }
  }
  CameraMove orbit = move(CameraMove::kOrbit);
  orbit.angle2 = kNan;
  cases.push_back({orbit, "angle2:"});
  for (const int op : {CameraMove::kTranslate, CameraMove::kLookAt, CameraMove::kScale}) {
    CameraMove m = move(op);
    m.vector = Eigen::Vector3d(0, kNan, 0);
    cases.push_back({m, "vector.y:"});
    m.vector = Eigen::Vector3d(5000, 0, 0);
    cases.push_back({m, "vector.x:"});
  }
  for (const int op : {CameraMove::kScale, CameraMove::kZoom}) {
    for (const double bad : {0.0, -1.0, kNan, 1000.0}) {
      CameraMove m = move(op);
      m.factor = bad;
      cases.push_back({m, "factor:"});
    }
  }
  CameraMove eye = move(CameraMove::kSetEye);
  eye.vector = Eigen::Vector3d(1, 2, kInf);
  cases.push_back({eye, "vector.z:"});
  for (const double bad : {kNan, 0.0, 9.0 * M_PI / 180, 121.0 * M_PI / 180, 7.0}) {
    CameraMove m = move(CameraMove::kSetFov);
    m.angle = bad;
    cases.push_back({m, "angle:"});
  }
  for (const auto& [w, h, field] : {std::tuple{0, 100, "width:"}, std::tuple{5000, 100, "width:"},
                                    std::tuple{100, -3, "height:"}, std::tuple{100, 9999, "height:"}}) {
    CameraMove m = move(CameraMove::kSetImageSize);
    m.width = w;
    m.height = h;
    cases.push_back({m, field});
  }
  cases.push_back({move(0), "operation:"});
  cases.push_back({move(99), "operation:"});
  for (const Case& c : cases) {
    Camera camera;
    const Camera before = camera;
    const std::string reason = ApplyCameraMove(c.move, &camera);
    EXPECT_EQ(reason.rfind(c.field, 0), 0u) << reason;
    EXPECT_NE(reason.find("allowed"), std::string::npos) << reason;
    EXPECT_EQ(camera.eye, before.eye);
    EXPECT_EQ(camera.scene.matrix(), before.scene.matrix());
    EXPECT_EQ(camera.width, before.width);
    EXPECT_EQ(camera.fov_y, before.fov_y);
  }
}

TEST(CameraMoves, ValidMovesApply) {
  Camera camera;
  CameraMove size;
  size.operation = CameraMove::kSetImageSize;
  size.width = 320;
  size.height = 200;
  EXPECT_EQ(ApplyCameraMove(size, &camera), "");
  EXPECT_EQ(camera.width, 320);
  CameraMove look;
  look.operation = CameraMove::kLookAt;
  look.vector = Eigen::Vector3d(0, 3, 0);
  EXPECT_EQ(ApplyCameraMove(look, &camera), "");
  EXPECT_EQ(camera.target, Eigen::Vector3d(0, 3, 0));
  CameraMove at_eye = look;
  at_eye.vector = camera.eye;  // looking at itself: refused
  EXPECT_NE(ApplyCameraMove(at_eye, &camera), "");
  EXPECT_EQ(camera.target, Eigen::Vector3d(0, 3, 0));
}

CameraMove Move(int operation) {
  CameraMove move;
  move.operation = operation;
  return move;
}

CameraMove WithVector(int operation, const Eigen::Vector3d& vector) {
  CameraMove move = Move(operation);
  move.vector = vector;
  return move;
}

/// Whether `camera` is as `before` was: eye, target, field of view, the scene's transforms.
void ExpectUnchanged(const Camera& camera, const Camera& before) {
  EXPECT_EQ(camera.eye, before.eye);
  EXPECT_EQ(camera.target, before.target);
  EXPECT_EQ(camera.fov_y, before.fov_y);
  EXPECT_EQ(camera.scene.matrix(), before.scene.matrix());
}

TEST(CameraMoves, ZoomSetEyeAndSetFovApply) {
  Camera camera;
  const double distance = (camera.eye - camera.target).norm();
  CameraMove zoom = Move(CameraMove::kZoom);
  zoom.factor = 2;
  EXPECT_EQ(ApplyCameraMove(zoom, &camera), "");
  EXPECT_NEAR((camera.eye - camera.target).norm(), distance / 2, 1e-12);
  zoom.factor = CameraMove::kMaxFactor;  // clamped at the nearest, not rejected
  EXPECT_EQ(ApplyCameraMove(zoom, &camera), "");
  EXPECT_NEAR((camera.eye - camera.target).norm(), Camera::kMinZoomDistance, 1e-12);

  const Eigen::Vector3d eye(-1, 0.5, 3);
  EXPECT_EQ(ApplyCameraMove(WithVector(CameraMove::kSetEye, eye), &camera), "");
  EXPECT_EQ(camera.eye, eye);
  EXPECT_EQ(camera.target, Camera{}.target);

  CameraMove fov = Move(CameraMove::kSetFov);
  fov.angle = 55 * M_PI / 180;
  EXPECT_EQ(ApplyCameraMove(fov, &camera), "");
  EXPECT_EQ(camera.fov_y, fov.angle);
  for (const double degrees : {CameraMove::kMinFov, CameraMove::kMaxFov}) {  // the ends are allowed
    fov.angle = degrees * M_PI / 180;
    EXPECT_EQ(ApplyCameraMove(fov, &camera), "") << degrees;
  }
}

TEST(CameraMoves, AFieldOfViewOutOfRangeIsReportedInDegrees) {
  for (const double degrees : {200.0, 5.0, -30.0}) {
    Camera camera;
    CameraMove fov = Move(CameraMove::kSetFov);
    fov.angle = degrees * M_PI / 180;  // as flagctl sends it
    char expected[128];
    std::snprintf(expected, sizeof(expected), "angle: %g degrees is out of range; allowed %g .. %g degrees",
                  degrees, CameraMove::kMinFov, CameraMove::kMaxFov);
    const std::string reason = ApplyCameraMove(fov, &camera);
    EXPECT_EQ(reason.rfind(expected, 0), 0u) << reason;
    EXPECT_EQ(camera.fov_y, Camera{}.fov_y);
  }
}

// Rotations and the orbit's angles are typed in degrees (flagctl, the live view): so are their reasons.
TEST(CameraMoves, AnAngleOutOfRangeIsReportedInDegrees) {
  for (const int operation : {CameraMove::kRotateX, CameraMove::kOrbit}) {
    for (const double degrees : {1e9, -400.0}) {
      Camera camera;
      CameraMove move = Move(operation);
      move.angle = degrees * M_PI / 180;  // as flagctl sends it
      char expected[128];
      std::snprintf(expected, sizeof(expected),
                    "angle: %g degrees is out of range; allowed -360 .. 360 degrees", degrees);
      const std::string reason = ApplyCameraMove(move, &camera);
      EXPECT_EQ(reason, expected);
      EXPECT_EQ(camera.eye, Camera{}.eye);
    }
  }
  CameraMove orbit = Move(CameraMove::kOrbit);
  orbit.angle2 = 720 * M_PI / 180;
  Camera camera;
  EXPECT_EQ(ApplyCameraMove(orbit, &camera),
            "angle2: 720 degrees is out of range; allowed -360 .. 360 degrees");
}

TEST(CameraMoves, OrbitNeverFailsBecauseOfTheGround) {
  Camera camera;
  CameraMove orbit = Move(CameraMove::kOrbit);
  orbit.angle2 = -60 * M_PI / 180;  // flagctl camera orbit 0 -60
  EXPECT_EQ(ApplyCameraMove(orbit, &camera), "");
  EXPECT_NEAR(camera.EyeHeight(), Camera::kMinEyeHeight, 1e-9);
  EXPECT_EQ(ApplyCameraMove(orbit, &camera), "");  // at the ground already: it stays
  EXPECT_NEAR(camera.EyeHeight(), Camera::kMinEyeHeight, 1e-9);
  orbit.angle = 1.0;  // round the target at the least height
  orbit.angle2 = 0;
  const Eigen::Vector3d before = camera.eye;
  EXPECT_EQ(ApplyCameraMove(orbit, &camera), "");
  EXPECT_GT((camera.eye - before).norm(), 1.0);
  EXPECT_NEAR(camera.EyeHeight(), Camera::kMinEyeHeight, 1e-9);
}

TEST(CameraMoves, MovesThatWouldTakeTheEyeUnderTheGroundAreRejected) {
  const Camera start;
  const double height = start.EyeHeight();
  struct Case {
    CameraMove move;
    const char* field;
  };
  std::vector<Case> cases = {
      {WithVector(CameraMove::kTranslate, Eigen::Vector3d(0, -height - 1, 0)), "vector:"},
      {WithVector(CameraMove::kTranslate, Eigen::Vector3d(0, Camera::kMinEyeHeight / 2 - height, 0)),
       "vector:"},  // above the ground, but nearer than allowed
      {WithVector(CameraMove::kSetEye, Eigen::Vector3d(1, -0.5, 3)), "vector:"},
      {WithVector(CameraMove::kSetEye, Eigen::Vector3d(1, Camera::kMinEyeHeight / 2, 3)), "vector:"}};
  // Scaling the world by 0.2 about a point 10 m up lifts it, and with it the ground, over the eye:
  // the eye lands at centre + (eye - centre) / 0.2 in the world.
  CameraMove scale = WithVector(CameraMove::kScale, Eigen::Vector3d(0, 10, 0));
  scale.factor = 0.2;
  ASSERT_LT(10 + (height - 10) / 0.2, 0);
  cases.push_back({scale, "factor:"});
  // Turning the world about x through the target: one way lifts the ground over the eye.
  int rotations_under = 0;
  for (const double angle : {1.2, -1.2}) {
    Camera turned = start;
    turned.RotateScene(Eigen::Vector3d::UnitX(), angle);
    CameraMove rotate = Move(CameraMove::kRotateX);
    rotate.angle = angle;
    if (turned.EyeHeight() < Camera::kMinEyeHeight) {
      cases.push_back({rotate, "angle:"});
      ++rotations_under;
    } else {
      Camera camera = start;
      EXPECT_EQ(ApplyCameraMove(rotate, &camera), "") << angle;
    }
  }
  EXPECT_EQ(rotations_under, 1);
  for (const Case& c : cases) {
    Camera camera = start;
    const std::string reason = ApplyCameraMove(c.move, &camera);
    EXPECT_EQ(reason.rfind(c.field, 0), 0u) << reason;
    EXPECT_NE(reason.find("ground"), std::string::npos) << reason;
    EXPECT_NE(reason.find("allowed at least"), std::string::npos) << reason;
    ExpectUnchanged(camera, start);
  }
  // Along the ground is fine.
  Camera camera = start;
  EXPECT_EQ(ApplyCameraMove(WithVector(CameraMove::kTranslate, Eigen::Vector3d(0, 0, 2)), &camera), "");
  const Eigen::Vector3d low(1, Camera::kMinEyeHeight, 3);
  EXPECT_EQ(ApplyCameraMove(WithVector(CameraMove::kSetEye, low), &camera), "");
  EXPECT_EQ(camera.eye, low);
}

TEST(CameraMoves, AnEyeUnderTheGroundMayRiseButNotSink) {
  Camera start;
  start.eye = Eigen::Vector3d(0.8, -1, 4);  // as a scene file might put it
  Camera camera = start;
  EXPECT_NE(ApplyCameraMove(WithVector(CameraMove::kTranslate, Eigen::Vector3d(0, -0.5, 0)), &camera), "");
  ExpectUnchanged(camera, start);
  EXPECT_EQ(ApplyCameraMove(WithVector(CameraMove::kTranslate, Eigen::Vector3d(1, 0, 0)), &camera), "");
  EXPECT_EQ(ApplyCameraMove(WithVector(CameraMove::kTranslate, Eigen::Vector3d(0, 0.5, 0)), &camera), "");
  EXPECT_EQ(camera.eye.y(), -0.5);
}

}  // namespace
}  // namespace flagsim::render
