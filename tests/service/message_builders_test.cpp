#include "server/service/message_builders.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "messages/checked_decode.hpp"
#include "server/scene/parameter_table.hpp"
#include "server/service/frame_painter.hpp"
#include "tests/messages/message_fixtures.hpp"

namespace flagsim {
namespace {

TEST(MessageBuilders, StateCarriesEveryNodeAndTheHash) {
  Session session{Scene{}};
  for (int i = 0; i < 20; ++i) session.Step();
  const state_t state = MakeStateMessage(session, 123);
  const auto& sim = session.simulation();
  EXPECT_EQ(state.step, 20);
  EXPECT_EQ(state.cols * state.rows, sim.model().num_nodes());
  ASSERT_EQ(state.num_values, 3 * sim.model().num_nodes());
  EXPECT_EQ(static_cast<uint64_t>(state.state_hash), sim.Hash());
  const int last = sim.model().num_nodes() - 1;
  EXPECT_EQ(state.position[3 * last + 2], sim.state().z[last]);
  // and it survives the wire
  const auto bytes = testing::Encode(state);
  std::string error;
  const auto decoded = wire::CheckedDecode<state_t>(bytes.data(), bytes.size(), 1 << 20, &error);
  ASSERT_TRUE(decoded) << error;
  EXPECT_EQ(decoded->position, state.position);
}

TEST(MessageBuilders, StateCarriesTheKineticEnergyOfTheFreeNodes) {
  Session session{Scene{}};
  for (int i = 0; i < 40; ++i) session.Step();
  // 1/2 sum m v^2 over the nodes that are not pinned to the pole, worked out here.
  const auto& model = session.simulation().model();
  const auto& now = session.simulation().state();
  double expected = 0;
  int free_nodes = 0;
  for (int i = 0; i < model.num_nodes(); ++i) {
    if (model.inverse_mass[i] == 0) continue;
    ++free_nodes;
    const double speed_squared =
        double(now.vx[i]) * now.vx[i] + double(now.vy[i]) * now.vy[i] + double(now.vz[i]) * now.vz[i];
    expected += 0.5 * double(model.mass[i]) * speed_squared;
  }
  ASSERT_LT(free_nodes, model.num_nodes());  // some are pinned
  ASSERT_GT(expected, 0);                    // the flag moves
  const state_t state = MakeStateMessage(session, 1);
  EXPECT_NEAR(state.kinetic_energy, expected, 1e-12 * expected);
  const auto bytes = testing::Encode(state);
  std::string error;
  const auto decoded = wire::CheckedDecode<state_t>(bytes.data(), bytes.size(), 1 << 20, &error);
  ASSERT_TRUE(decoded) << error;
  EXPECT_EQ(decoded->kinetic_energy, state.kinetic_energy);
}

TEST(MessageBuilders, StateCarriesTheGustStrengthInForce) {
  Session session{Scene{}};
  const double dt = session.scene().sim.dt, from = Scene{}.wind.gust;
  EXPECT_EQ(MakeStateMessage(session, 1).wind_gust, from);
  sim::WindSettings wind = Scene{}.wind;
  wind.gust = from + 0.4;
  wind.ramp_time = 10 * dt;  // the gusts grow over ten steps
  ASSERT_EQ(session.ApplyWind(wind), "");
  for (int i = 0; i < 4; ++i) session.Step();
  EXPECT_NEAR(MakeStateMessage(session, 1).wind_gust, from + 0.4 * 4 / 10, 1e-9);
  for (int i = 0; i < 10; ++i) session.Step();
  EXPECT_EQ(MakeStateMessage(session, 1).wind_gust, wind.gust);
}

TEST(MessageBuilders, FramesCarryTheCameraAsDrawn) {
  Session session{Scene{}};
  render::CameraMove move;
  move.operation = render::CameraMove::kSetEye;
  move.vector = Eigen::Vector3d(1, 1.5, 3);
  ASSERT_EQ(session.ApplyCamera(move), "");
  move.operation = render::CameraMove::kSetFov;
  move.angle = 50 * M_PI / 180;
  ASSERT_EQ(session.ApplyCamera(move), "");
  move.operation = render::CameraMove::kSetImageSize;
  move.width = 96;
  move.height = 64;
  ASSERT_EQ(session.ApplyCamera(move), "");
  const render::Camera& camera = session.scene().camera;
  const FrameInfo info = MakeFrameInfo(session, 5);
  EXPECT_EQ(info.camera_eye, Eigen::Vector3d(1, 1.5, 3));
  EXPECT_EQ(info.camera_target, camera.target);
  EXPECT_NEAR(info.camera_fov, 50, 1e-12);  // degrees
  EXPECT_EQ(info.view, camera.View());
  // In the manifest, and through the wire.
  TileStream stream(64);
  FramePainter painter;
  const frame_t manifest = stream.Encode(painter.Paint(FrameInput::Of(session, 5), 1), info, 1).manifest;
  const auto bytes = testing::Encode(manifest);
  std::string error;
  const auto decoded = wire::CheckedDecode<frame_t>(bytes.data(), bytes.size(), 1 << 20, &error);
  ASSERT_TRUE(decoded) << error;
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(decoded->camera_eye[k], info.camera_eye[k]);
    EXPECT_EQ(decoded->camera_target[k], camera.target[k]);
  }
  EXPECT_NEAR(decoded->camera_fov, 50, 1e-12);
}

TEST(MessageBuilders, ParamsListTheWholeTableWithCurrentValues) {
  Scene scene;
  scene.sim.forces.stiffness = 777;
  const params_t params = MakeParamsMessage(scene, 1);
  ASSERT_EQ(params.num_parameters, static_cast<int32_t>(ParameterTable::Get().parameters().size()));
  bool found = false;
  for (const parameter_t& row : params.parameters) {
    if (row.name != "stiffness") continue;
    found = true;
    EXPECT_EQ(row.value, 777);
    EXPECT_EQ(row.value_text, "777");
    EXPECT_EQ(row.unit, "N/m");
    EXPECT_EQ(row.default_value, Scene{}.sim.forces.stiffness);
  }
  EXPECT_TRUE(found);
  const auto bytes = testing::Encode(params);
  std::string error;
  EXPECT_TRUE(wire::CheckedDecode<params_t>(bytes.data(), bytes.size(), 1 << 20, &error)) << error;
}

TEST(MessageBuilders, StatusRatesAreOverTheWindow) {
  Session session{Scene{}};
  ServerStats stats;
  stats.steps = 250;
  stats.step_seconds = 0.05;
  stats.states_published = 30;
  stats.commands_rejected = 4;
  StatusWindow window;
  window.wall_seconds = 0.5;
  window.sim_seconds = 0.25;
  window.bytes = 1000;
  const status_t status = MakeStatusMessage(session, stats, window, 1);
  EXPECT_DOUBLE_EQ(status.steps_per_second, 500);
  EXPECT_DOUBLE_EQ(status.step_time_us, 200);
  EXPECT_DOUBLE_EQ(status.state_rate_hz, 60);
  EXPECT_DOUBLE_EQ(status.real_time_factor, 0.5);
  EXPECT_DOUBLE_EQ(status.bytes_per_second, 2000);
  EXPECT_EQ(status.commands_rejected, 4);
  EXPECT_EQ(status.integrator, "symplectic_euler");
}

TEST(MessageBuilders, TimelineListsEveryKeyAndWhatItSets) {
  sim::Timeline timeline;
  sim::Keyframe wind;
  wind.time = 1;
  wind.law = sim::ControlLaw::kCubic;
  wind.wind = sim::WindControl{{3, 0, -4}, 0.25};
  timeline.Add(wind);
  sim::Keyframe rest;
  rest.time = 3.5;
  rest.parameters = {{"stiffness", 2500}, {"gravity", 9}};
  rest.camera = sim::CameraControl{{1, 2, 3}, {0, 2, 0}, 55};
  timeline.Add(rest);
  timeline.SetLoop(true);
  timeline.Play();
  timeline.Seek(1.25);
  const timeline_t message = MakeTimelineMessage(timeline, 42, 7);
  EXPECT_EQ(message.step, 42);
  EXPECT_TRUE(message.playing);
  EXPECT_TRUE(message.loop);
  EXPECT_EQ(message.position, 1.25);
  EXPECT_EQ(message.last_key_time, 3.5);
  ASSERT_EQ(message.num_keys, 2);
  const timeline_key_t& first = message.keys[0];
  EXPECT_EQ(first.law, timeline_key_t::LAW_CUBIC);
  EXPECT_TRUE(first.has_wind);
  EXPECT_EQ(first.wind_velocity[2], -4);
  EXPECT_EQ(first.wind_gust, 0.25);
  EXPECT_FALSE(first.has_camera);
  EXPECT_EQ(first.num_parameters, 0);
  const timeline_key_t& second = message.keys[1];
  EXPECT_EQ(second.law, timeline_key_t::LAW_LINEAR);
  EXPECT_FALSE(second.has_wind);
  EXPECT_EQ(second.names, (std::vector<std::string>{"stiffness", "gravity"}));
  EXPECT_EQ(second.values, (std::vector<double>{2500, 9}));
  EXPECT_TRUE(second.has_camera);
  EXPECT_EQ(second.camera_eye[2], 3);
  EXPECT_EQ(second.camera_fov, 55);
  // and it survives the wire
  const auto bytes = testing::Encode(message);
  std::string error;
  const auto decoded = wire::CheckedDecode<timeline_t>(bytes.data(), bytes.size(), 1 << 20, &error);
  ASSERT_TRUE(decoded) << error;
  EXPECT_EQ(decoded->keys[1].names, second.names);
}

}  // namespace
}  // namespace flagsim
