// JSON requests into commands: each field where it belongs, degrees into radians, and a
// request of the wrong shape refused with the field's name.
#include "client/gateway/command_requests.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace flagsim::gateway {
namespace {

using nlohmann::json;

TEST(CommandRequests, Wind) {
  wind_command_t command{};
  ASSERT_EQ(WindCommandOf(json::parse(R"({"velocity": [8, 0, -2.5], "gust": 0.3, "ramp": 2})"), &command),
            "");
  EXPECT_EQ(command.velocity[0], 8);
  EXPECT_EQ(command.velocity[2], -2.5);
  EXPECT_EQ(command.gust, 0.3);
  EXPECT_EQ(command.ramp_time, 2);
  EXPECT_EQ(WindCommandOf(json::parse(R"({"gust": 0.3})"), &command), "velocity: required, [x, y, z] in m");
  EXPECT_EQ(WindCommandOf(json::parse(R"({"velocity": [1, 2]})"), &command),
            "velocity: must be [x, y, z], three numbers");
  EXPECT_EQ(WindCommandOf(json::parse(R"({"velocity": [1, 2, 3], "gust": "high"})"), &command),
            "gust: must be a number");
  EXPECT_EQ(WindCommandOf(json::parse("[1, 2, 3]"), &command), "the request must be a JSON object");
}

TEST(CommandRequests, SetTurnsValuesIntoText) {
  param_command_t command{};
  ASSERT_EQ(
      SetCommandOf(json::parse(R"({"parameters": {"stiffness": 1500, "dt": 0.0015, "relative_wind": true,
                                                        "integrator": "rk4"}})"),
                   &command),
      "");
  ASSERT_EQ(command.num_assignments, 4);
  std::map<std::string, std::string> assigned;
  for (int i = 0; i < 4; ++i) assigned[command.names[i]] = command.values[i];
  EXPECT_EQ(assigned["stiffness"], "1500");
  EXPECT_EQ(std::stod(assigned["dt"]), 0.0015);
  EXPECT_EQ(assigned["relative_wind"], "true");
  EXPECT_EQ(assigned["integrator"], "rk4");
  EXPECT_FALSE(command.reset_to_scene);
  param_command_t reset{};
  EXPECT_EQ(SetCommandOf(json::parse(R"({"reset": true})"), &reset), "");
  EXPECT_TRUE(reset.reset_to_scene);
  param_command_t nothing{};
  EXPECT_EQ(SetCommandOf(json::parse(R"({})"), &nothing), "parameters: nothing to set");
  param_command_t bad{};
  EXPECT_EQ(SetCommandOf(json::parse(R"({"parameters": {"stiffness": [1]}})"), &bad),
            "parameters.stiffness: a value must be a number, true or false, or a name; got array");
}

TEST(CommandRequests, CameraAnglesAreDegreesOnTheWayIn) {
  camera_command_t command{};
  ASSERT_EQ(
      CameraCommandOf(json::parse(R"({"operation": "orbit", "degrees": 90, "degrees2": -30})"), &command),
      "");
  EXPECT_EQ(command.operation, camera_command_t::ORBIT);
  EXPECT_DOUBLE_EQ(command.angle, M_PI / 2);
  EXPECT_DOUBLE_EQ(command.angle2, -M_PI / 6);
  ASSERT_EQ(CameraCommandOf(json::parse(R"({"operation": "zoom", "factor": 1.25})"), &command), "");
  EXPECT_EQ(command.operation, camera_command_t::ZOOM);
  EXPECT_EQ(command.factor, 1.25);
  ASSERT_EQ(CameraCommandOf(json::parse(R"({"operation": "eye", "vector": [1, 2, 3]})"), &command), "");
  EXPECT_EQ(command.operation, camera_command_t::SET_EYE);
  EXPECT_EQ(command.vector[1], 2);
  ASSERT_EQ(CameraCommandOf(json::parse(R"({"operation": "fov", "degrees": 60})"), &command), "");
  EXPECT_EQ(command.operation, camera_command_t::SET_FOV);
  EXPECT_DOUBLE_EQ(command.angle, M_PI / 3);
  ASSERT_EQ(CameraCommandOf(json::parse(R"({"operation": "size", "width": 640, "height": 360})"), &command),
            "");
  EXPECT_EQ(command.width, 640);
  EXPECT_EQ(CameraCommandOf(json::parse(R"({"operation": "translate"})"), &command),
            "vector: required, [x, y, z] in m");
  const std::string unknown = CameraCommandOf(json::parse(R"({"operation": "spin"})"), &command);
  EXPECT_EQ(unknown.rfind("operation: 'spin' is not one; allowed rotate_x, ", 0), 0u) << unknown;
}

TEST(CommandRequests, KeyframeKeysCarryWhatTheySet) {
  keyframe_command_t command{};
  ASSERT_EQ(KeyframeCommandOf(json::parse(R"({"operation": "add", "key": {"time": 4, "law": "cubic",
      "wind": {"velocity": [7, 0, 0], "gust": 0.2}, "parameters": {"stiffness": 1500},
      "camera": {"eye": [3, 2, 4], "target": [0.8, 2.2, 0], "fov": 40}}})"),
                              &command),
            "");
  EXPECT_EQ(command.operation, keyframe_command_t::ADD);
  EXPECT_EQ(command.key.time, 4);
  EXPECT_EQ(command.key.law, timeline_key_t::LAW_CUBIC);
  EXPECT_TRUE(command.key.has_wind);
  EXPECT_EQ(command.key.wind_gust, 0.2);
  ASSERT_EQ(command.key.num_parameters, 1);
  EXPECT_EQ(command.key.names[0], "stiffness");
  EXPECT_TRUE(command.key.has_camera);
  EXPECT_EQ(command.key.camera_fov, 40);
  keyframe_command_t seek{};
  ASSERT_EQ(KeyframeCommandOf(json::parse(R"({"operation": "seek", "time": 2.5})"), &seek), "");
  EXPECT_EQ(seek.time, 2.5);
  EXPECT_EQ(KeyframeCommandOf(json::parse(R"({"operation": "add"})"), &seek),
            "key: required for add and change, an object");
  EXPECT_EQ(
      KeyframeCommandOf(json::parse(R"({"operation": "add", "key": {"time": 1, "law": "wiggly"}})"), &seek),
      "key.law: must be one of step, linear, smooth, cubic");
  EXPECT_EQ(
      KeyframeCommandOf(
          json::parse(R"({"operation": "add", "key": {"time": 1, "camera": {"eye": [1, 2, 3]}}})"), &seek),
      "key.camera.target: required, [x, y, z] in m");
}

}  // namespace
}  // namespace flagsim::gateway
