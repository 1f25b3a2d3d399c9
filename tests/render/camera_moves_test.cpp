#include "render/camera_moves.hpp"

#include <gtest/gtest.h>

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
  for (const double bad : {0.0, -1.0, kNan, 1000.0}) {
    CameraMove m = move(CameraMove::kScale);
    m.factor = bad;
    cases.push_back({m, "factor:"});
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

}  // namespace
}  // namespace flagsim::render
