// Keyframe commands over the bus (memq://): keys added, played and listed on TIMELINE, every
// operation, hostile and lying bytes, and the ACK of a command that a playing timeline overrides.
#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <optional>

#include "tests/messages/message_fixtures.hpp"
#include "tests/service/command_intake_fixture.hpp"

namespace flagsim {
namespace {

keyframe_command_t KeyframeCommand(int8_t operation, double time = 0) {
  keyframe_command_t command{};
  command.operation = operation;
  command.time = time;
  return command;
}

/// An ADD of a key at `time` setting the stiffness to `stiffness`.
keyframe_command_t AddStiffness(double time, double stiffness) {
  keyframe_command_t command = KeyframeCommand(keyframe_command_t::ADD);
  command.key.time = time;
  command.key.law = timeline_key_t::LAW_LINEAR;
  command.key.names = {"stiffness"};
  command.key.values = {stiffness};
  command.key.num_parameters = 1;
  return command;
}

TEST_F(CommandIntakeTest, KeyframesAreAddedPlayedAndListedOnTimeline) {
  std::optional<timeline_t> listed;
  bus_.Subscribe(channels_.timeline, [&listed](const std::string&, const uint8_t* data, size_t size) {
    std::string error;
    listed = wire::CheckedDecode<timeline_t>(data, size, 1 << 20, &error);
  });
  CommandOutcome outcome = client_.Send(channels_.keyframe, testing::SomeKeyframeCommand());
  ASSERT_EQ(outcome.result, CommandOutcome::kAccepted) << outcome.reason;
  outcome = client_.Send(channels_.keyframe, AddStiffness(0, 1000));
  ASSERT_EQ(outcome.result, CommandOutcome::kAccepted) << outcome.reason;
  const sim::Timeline& timeline = scene().timeline;
  ASSERT_EQ(timeline.keys().size(), 2u);
  const sim::Keyframe& key = timeline.keys()[1];  // SomeKey, at 2 s
  EXPECT_EQ(key.time, 2);
  EXPECT_EQ(key.law, sim::ControlLaw::kSmooth);
  EXPECT_EQ(key.wind->velocity, (sim::Vec3{6, 0, 0}));
  EXPECT_EQ(*key.Parameter("damping"), 0.1);
  EXPECT_EQ(key.camera->fov, 40);
  server_.Tick(clock_.now());  // TIMELINE follows an accepted KEYFRAME
  bus_.HandleAll();
  ASSERT_TRUE(listed);
  ASSERT_EQ(listed->num_keys, 2);
  EXPECT_EQ(listed->keys[1].names, testing::SomeKey().names);
  EXPECT_EQ(listed->keys[1].law, timeline_key_t::LAW_SMOOTH);
  EXPECT_FALSE(listed->playing);
  EXPECT_EQ(listed->last_key_time, 2);

  ASSERT_EQ(client_.Send(channels_.keyframe, KeyframeCommand(keyframe_command_t::PLAY)).result,
            CommandOutcome::kAccepted);
  EXPECT_TRUE(scene().timeline.playing());
  while (scene().timeline.position() < 0.5) clock_.Step(server_);
  // Past the glide from the scene's 2000, on the line from 1000 at 0 s to 1500 at 2 s: the last
  // step started dt before the position.
  const double position = scene().timeline.position();
  ASSERT_LT(position, 2);
  EXPECT_NEAR(scene().sim.forces.stiffness, 1000 + 250 * (position - scene().sim.dt), 1e-6);
  EXPECT_EQ(stats().commands_accepted, 3);
}

TEST_F(CommandIntakeTest, EveryKeyframeOperationIsTaken) {
  ASSERT_EQ(client_.Send(channels_.keyframe, AddStiffness(0, 1000)).result, CommandOutcome::kAccepted);
  ASSERT_EQ(client_.Send(channels_.keyframe, AddStiffness(4, 3000)).result, CommandOutcome::kAccepted);
  keyframe_command_t change = AddStiffness(5, 2500);
  change.operation = keyframe_command_t::CHANGE;
  change.time = 4;
  change.keep_law = true;
  change.key.law = 99;  // not read
  ASSERT_EQ(client_.Send(channels_.keyframe, change).result, CommandOutcome::kAccepted);
  EXPECT_EQ(*scene().timeline.Find(5)->Parameter("stiffness"), 2500);
  keyframe_command_t speed = KeyframeCommand(keyframe_command_t::SPEED);
  speed.speed = 2;
  keyframe_command_t loop = KeyframeCommand(keyframe_command_t::LOOP);
  loop.loop = true;
  for (const keyframe_command_t& command :
       {speed, loop, KeyframeCommand(keyframe_command_t::SEEK, 3), KeyframeCommand(keyframe_command_t::PLAY),
        KeyframeCommand(keyframe_command_t::PAUSE)}) {
    const CommandOutcome outcome = client_.Send(channels_.keyframe, command);
    EXPECT_EQ(outcome.result, CommandOutcome::kAccepted) << int(command.operation) << ": " << outcome.reason;
  }
  EXPECT_EQ(scene().timeline.speed(), 2);
  EXPECT_TRUE(scene().timeline.loop());
  EXPECT_FALSE(scene().timeline.playing());
  EXPECT_GE(scene().timeline.position(), 3);
  ASSERT_EQ(client_.Send(channels_.keyframe, KeyframeCommand(keyframe_command_t::REMOVE, 0)).result,
            CommandOutcome::kAccepted);
  EXPECT_EQ(scene().timeline.keys().size(), 1u);
  ASSERT_EQ(client_.Send(channels_.keyframe, KeyframeCommand(keyframe_command_t::CLEAR)).result,
            CommandOutcome::kAccepted);
  EXPECT_TRUE(scene().timeline.keys().empty());
}

TEST_F(CommandIntakeTest, HostileKeyframeCommandsAreRejectedWithTheFieldAndChangeNothing) {
  // The key lies far ahead: the server steps as fast as it can while the client waits, and the
  // timeline must still be playing, not past its end, when the last command is answered.
  ASSERT_EQ(client_.Send(channels_.keyframe, AddStiffness(1000, 1500)).result, CommandOutcome::kAccepted);
  ASSERT_EQ(client_.Send(channels_.keyframe, KeyframeCommand(keyframe_command_t::PLAY)).result,
            CommandOutcome::kAccepted);
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  std::vector<std::pair<keyframe_command_t, std::string>> hostile;
  const auto add = [&](keyframe_command_t command, const std::string& field) {
    hostile.emplace_back(command, field);
  };
  keyframe_command_t command = AddStiffness(nan, 1000);
  add(command, "key.time:");
  add(AddStiffness(-inf, 1000), "key.time:");
  add(AddStiffness(1e300, 1000), "key.time:");
  add(AddStiffness(2, nan), "key.parameters.stiffness: nan is not a finite number; allowed 1 .. 1e+05 N/m");
  add(AddStiffness(2, inf), "key.parameters.stiffness:");
  add(AddStiffness(2, -5), "key.parameters.stiffness: -5 is out of range");
  command = AddStiffness(2, 1000);
  command.key.names = {"colour"};
  add(command, "key.parameters: unknown parameter 'colour'");
  command.key.names = {"cols"};
  add(command, "key.parameters.cols: cannot be animated");
  command.key.names = {std::string(5000, 'x')};
  add(command, "key.names[0]: 5000 characters; allowed up to 64");
  command = AddStiffness(2, 1000);
  command.key.num_parameters = 65;
  command.key.names.assign(65, "gravity");
  command.key.values.assign(65, 9.0);
  add(command, "key.num_parameters: 65; allowed 0 .. 64");
  command = AddStiffness(2, 1000);
  command.key.law = 4;
  add(command, "key.law: 4 is not a law");
  command = AddStiffness(2, 1000);
  command.key.has_wind = true;
  command.key.wind_velocity[2] = nan;
  add(command, "key.wind.velocity.z:");
  command.key.wind_velocity[2] = 100;
  add(command, "key.wind.velocity: speed 100");
  command.key.wind_velocity[2] = 5;
  command.key.wind_gust = inf;
  add(command, "key.wind.gust:");
  command = AddStiffness(2, 1000);
  command.key.has_camera = true;
  command.key.camera_eye[0] = 3;
  command.key.camera_fov = 500;
  add(command, "key.camera.fov: 500 is out of range; allowed 10 .. 120 degrees");
  command.key.camera_fov = 40;
  command.key.camera_target[1] = inf;
  add(command, "key.camera.target:");
  command = AddStiffness(2, 1000);
  command.key.num_parameters = 0;
  command.key.names.clear();
  command.key.values.clear();
  add(command, "key sets nothing");
  add(KeyframeCommand(12), "operation: 12 is not known; allowed 1 ADD");
  add(KeyframeCommand(-1), "operation:");
  add(KeyframeCommand(keyframe_command_t::SEEK, nan),
      "time: nan is not a finite number; allowed 0 .. 86400 s");
  add(KeyframeCommand(keyframe_command_t::REMOVE, 7), "time: no key at 7 s; keys at 1000 s");
  add(KeyframeCommand(keyframe_command_t::CHANGE, 7), "time: no key at 7 s");
  for (const double speed : {0.0, -1.0, nan, inf, 1e9}) {
    command = KeyframeCommand(keyframe_command_t::SPEED);
    command.speed = speed;
    add(command, "speed:");
  }
  const sim::Timeline before = scene().timeline;
  int64_t rejected = stats().commands_rejected;
  for (const auto& [each, field] : hostile) {
    const CommandOutcome outcome = client_.Send(channels_.keyframe, each);
    EXPECT_EQ(outcome.result, CommandOutcome::kRejected) << field;
    EXPECT_EQ(outcome.reason.rfind(field, 0), 0u) << "'" << outcome.reason << "' is not about " << field;
    EXPECT_EQ(stats().commands_rejected, ++rejected);
    // Unchanged, but for the position, which plays on.
    EXPECT_EQ(scene().timeline.keys(), before.keys());
    EXPECT_EQ(scene().timeline.speed(), before.speed());
    EXPECT_TRUE(scene().timeline.playing());
  }
  EXPECT_EQ(stats().commands_accepted, 2);
}

TEST_F(CommandIntakeTest, TruncatedAndLyingKeyframeBytesAreDropped) {
  const std::vector<uint8_t> valid = testing::Encode(testing::SomeKeyframeCommand());
  std::vector<std::vector<uint8_t>> hostile;
  for (size_t size = 0; size < valid.size(); size += 7)
    hostile.emplace_back(valid.begin(), valid.begin() + size);
  // The nested key's num_parameters, after fingerprint 8, utime 8, client_id "k" 4 + 2,
  // sequence 8, key_id "" 4 + 1, mac 32, operation 1, time 8, speed 8, loop 1, keep_law 1, and the
  // key's time 8, law 1, has_wind 1, wind_velocity 24, wind_gust 8.
  const size_t at = 8 + 8 + 6 + 8 + 5 + 32 + 1 + 8 + 8 + 1 + 1 + 8 + 1 + 1 + 24 + 8;
  ASSERT_EQ(valid[at + 3], 2);
  for (const uint32_t count : {0x7fffffffu, 0xffffffffu, 0x80000000u, 100000u}) {
    std::vector<uint8_t> lying = valid;
    for (int i = 0; i < 4; ++i) lying[at + i] = static_cast<uint8_t>(count >> (24 - 8 * i));
    hostile.push_back(lying);
  }
  for (const auto& bytes : hostile) {
    bus_.Publish(channels_.keyframe, bytes.data(), bytes.size());
    bus_.HandleAll();
  }
  EXPECT_EQ(stats().messages_dropped, int64_t(hostile.size()));
  EXPECT_EQ(stats().commands_accepted + stats().commands_rejected, 0);
  EXPECT_TRUE(scene().timeline.keys().empty());
  bus_.Publish(channels_.keyframe, valid.data(), valid.size());  // and the real thing is taken
  bus_.HandleAll();
  EXPECT_EQ(scene().timeline.keys().size(), 1u);
}

// A command that sets what a playing timeline drives is applied, and its ACK says for how long.
TEST_F(CommandIntakeTest, TheAckSaysWhenAPlayingTimelineDrivesWhatACommandSet) {
  // Keys at 0 and an hour on: the timeline plays throughout the test, setting the stiffness and
  // the camera but not the wind.
  ASSERT_EQ(client_.Send(channels_.keyframe, AddStiffness(0, 1000)).result, CommandOutcome::kAccepted);
  keyframe_command_t camera = AddStiffness(3600, 1000);
  camera.key.has_camera = true;
  camera.key.camera_eye[2] = 5;
  camera.key.camera_target[1] = 2;
  camera.key.camera_fov = 40;
  ASSERT_EQ(client_.Send(channels_.keyframe, camera).result, CommandOutcome::kAccepted);
  CommandOutcome outcome = SetParams({"stiffness", "gravity"}, {"1200", "9"});
  EXPECT_EQ(outcome.result, CommandOutcome::kAccepted);
  EXPECT_EQ(outcome.reason, "");  // paused: commands rule
  ASSERT_EQ(client_.Send(channels_.keyframe, KeyframeCommand(keyframe_command_t::PLAY)).result,
            CommandOutcome::kAccepted);
  outcome = SetParams({"stiffness", "gravity"}, {"1300", "9"});
  EXPECT_EQ(outcome.result, CommandOutcome::kAccepted);
  EXPECT_EQ(outcome.reason.rfind("applied, but the playing timeline sets stiffness from the next step", 0),
            0u)
      << outcome.reason;
  outcome = client_.Send(channels_.wind, testing::SomeWindCommand());
  EXPECT_EQ(outcome.result, CommandOutcome::kAccepted);
  EXPECT_EQ(outcome.reason, "");  // the timeline leaves the wind alone
  camera_command_t orbit{};
  orbit.operation = camera_command_t::ORBIT;
  orbit.angle = 0.3;
  outcome = client_.Send(channels_.camera, orbit);
  EXPECT_EQ(outcome.result, CommandOutcome::kAccepted);
  EXPECT_EQ(outcome.reason.rfind("applied, but the playing timeline sets the camera", 0), 0u)
      << outcome.reason;
  EXPECT_TRUE(scene().timeline.playing());
}

}  // namespace
}  // namespace flagsim
