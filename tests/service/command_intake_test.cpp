// The server's command side on an in-process bus (memq://): answers, validation, retries, and
// hostile bytes on every command channel.
#include "server/service/command_intake.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "client/command_client.hpp"
#include "server/scene/parameter_table.hpp"
#include "server/service/server.hpp"
#include "tests/messages/message_fixtures.hpp"
#include "tests/service/simulated_clock.hpp"

namespace flagsim {
namespace {

class CommandIntakeTest : public ::testing::Test {
 protected:
  // The server steps one step of the simulated clock each time the client looks for its answer:
  // accepted WIND and PARAM commands are answered once the flag has taken
  // CommandIntake::kSettleSteps steps under them.
  CommandIntakeTest()
      : bus_("memq://"),
        server_(bus_, channels_, Scene{}, clock_.ServerOnIt()),
        client_(bus_, channels_, 5.0, {}, clock_.Reader()) {
    client_.WhileWaiting([this] { clock_.Step(server_); });
  }

  const Scene& scene() const { return server_.session().scene(); }
  const ServerStats& stats() const { return server_.stats(); }

  CommandOutcome SetParams(std::vector<std::string> names, std::vector<std::string> values) {
    param_command_t command{};
    command.names = std::move(names);
    command.values = std::move(values);
    command.num_assignments = static_cast<int32_t>(command.names.size());
    return client_.Send(channels_.param, command);
  }

  /// Every parameter's current value, to check that a rejection changed nothing.
  std::vector<double> Values() const {
    std::vector<double> values;
    for (const Parameter& parameter : ParameterTable::Get().parameters())
      values.push_back(parameter.get(scene()));
    return values;
  }

  testing::SimulatedClock clock_;
  Bus bus_;
  Channels channels_;
  Server server_;
  CommandClient client_;
};

TEST_F(CommandIntakeTest, AcceptedWindIsAppliedAndAcknowledged) {
  wind_command_t command = testing::SomeWindCommand();
  const CommandOutcome outcome = client_.Send(channels_.wind, command);
  EXPECT_EQ(outcome.result, CommandOutcome::kAccepted) << outcome.reason;
  EXPECT_EQ(outcome.step, 0);
  EXPECT_EQ(scene().wind.velocity, (sim::Vec3{4, 0, 1}));
  EXPECT_EQ(scene().wind.gust, 0.25);
  EXPECT_EQ(server_.session().simulation().wind().target().ramp_time, 1.5);
  EXPECT_EQ(stats().commands_accepted, 1);
}

TEST_F(CommandIntakeTest, RejectedWindNamesTheFieldAndChangesNothing) {
  wind_command_t command{};
  command.velocity[1] = std::numeric_limits<double>::infinity();
  const CommandOutcome outcome = client_.Send(channels_.wind, command);
  EXPECT_EQ(outcome.result, CommandOutcome::kRejected);
  EXPECT_EQ(outcome.reason.rfind("velocity.y:", 0), 0u) << outcome.reason;
  EXPECT_EQ(scene().wind.velocity, Scene{}.wind.velocity);
  EXPECT_EQ(stats().commands_rejected, 1);
}

TEST_F(CommandIntakeTest, ParamsApplyTogetherOrNotAtAll) {
  const auto before = Values();
  CommandOutcome outcome = SetParams({"stiffness", "damping"}, {"1500", "nan"});
  EXPECT_EQ(outcome.result, CommandOutcome::kRejected);
  EXPECT_NE(outcome.reason.find("damping: 'nan' is not a finite number"), std::string::npos)
      << outcome.reason;
  EXPECT_EQ(Values(), before);  // stiffness was valid, but the command failed as a whole

  outcome = SetParams({"stiffness", "damping"}, {"1500", "0.2"});
  EXPECT_EQ(outcome.result, CommandOutcome::kAccepted) << outcome.reason;
  EXPECT_EQ(scene().sim.forces.stiffness, 1500);
  EXPECT_EQ(server_.session().simulation().params().forces.damping, 0.2);
}

TEST_F(CommandIntakeTest, EveryParameterRejectsNanInfinityAndOutOfRange) {
  for (const Parameter& parameter : ParameterTable::Get().parameters()) {
    std::vector<std::string> texts = {"nan", "inf", "-inf"};
    if (parameter.kind == ParameterKind::kReal || parameter.kind == ParameterKind::kInteger) {
      texts.push_back(parameter.Format(parameter.min_value - 1e6));
      texts.push_back(parameter.Format(parameter.max_value + 1e6));
    }
    for (const std::string& text : texts) {
      const auto before = Values();
      const CommandOutcome outcome = SetParams({parameter.name}, {text});
      EXPECT_EQ(outcome.result, CommandOutcome::kRejected) << parameter.name << "=" << text;
      EXPECT_EQ(outcome.reason.rfind(parameter.name + ":", 0), 0u) << outcome.reason;
      EXPECT_EQ(Values(), before);
    }
  }
}

TEST_F(CommandIntakeTest, ResetRestoresTheScene) {
  ASSERT_EQ(SetParams({"stiffness", "cols"}, {"900", "20"}).result, CommandOutcome::kAccepted);
  ASSERT_EQ(client_.Send(channels_.wind, testing::SomeWindCommand()).result, CommandOutcome::kAccepted);
  param_command_t reset{};
  reset.reset_to_scene = true;
  EXPECT_EQ(client_.Send(channels_.param, reset).result, CommandOutcome::kAccepted);
  EXPECT_EQ(scene().sim.forces.stiffness, Scene{}.sim.forces.stiffness);
  EXPECT_EQ(server_.session().simulation().model().cols, Scene{}.sim.cols);
  EXPECT_EQ(scene().wind.velocity, Scene{}.wind.velocity);
}

TEST_F(CommandIntakeTest, ARetryIsAnsweredAgainButAppliedOnce) {
  wind_command_t command = testing::SomeWindCommand();
  command.client_id = "retrying-client";
  command.sequence = 5;
  int acks = 0;
  bus_.Subscribe(channels_.ack, [&acks](const std::string&, const uint8_t*, size_t) { ++acks; });
  for (int i = 0; i < 3; ++i) bus_.Publish(channels_.wind, command);
  bus_.HandleAll();
  EXPECT_EQ(acks, 0);  // settling: retries wait for the one answer
  while (server_.session().simulation().state().step < CommandIntake::kSettleSteps) clock_.Step(server_);
  bus_.HandleAll();
  EXPECT_EQ(acks, 1);
  bus_.Publish(channels_.wind, command);  // a retry after the answer: the same answer again
  bus_.HandleAll();
  EXPECT_EQ(acks, 2);
  EXPECT_EQ(stats().commands_accepted, 1);
}

// Too few substeps for a stiff flag: the guard rolls back, multiplies the substeps, then hands
// the flag to a stable integrator; the command's ACK says so, and so do STATUS and PARAMS.
TEST_F(CommandIntakeTest, TheAckOfACommandThatBlewTheFlagUpSaysWhatTheGuardDid) {
  const CommandOutcome outcome = SetParams({"stiffness", "substeps"}, {"100000", "1"});
  EXPECT_EQ(outcome.result, CommandOutcome::kAccepted) << outcome.reason;
  EXPECT_NE(outcome.reason.find("the guard caught the flag"), std::string::npos) << outcome.reason;
  EXPECT_NE(outcome.reason.find("switched from symplectic_euler to xpbd"), std::string::npos)
      << outcome.reason;
  EXPECT_GT(server_.session().simulation().recoveries(), 0);
  EXPECT_EQ(scene().sim.integrator, sim::IntegratorKind::kXpbd);
}

TEST_F(CommandIntakeTest, CommandsWithoutAClientIdAreRejected) {
  wind_command_t command = testing::SomeWindCommand();
  command.client_id = "";
  std::optional<ack_t> answer;
  bus_.Subscribe(channels_.ack, [&answer](const std::string&, const uint8_t* data, size_t size) {
    std::string error;
    answer = wire::CheckedDecode<ack_t>(data, size, 1 << 16, &error);
  });
  bus_.Publish(channels_.wind, command);
  bus_.HandleAll();
  ASSERT_TRUE(answer);
  EXPECT_FALSE(answer->accepted);
  EXPECT_EQ(answer->reason.rfind("client_id:", 0), 0u);
}

// A client id of more than 64 characters or with a byte that is not printable ASCII is rejected
// with the rule it broke, and answered and logged as printable text cut to 64 characters: the
// id as sent (up to 64 KiB, escape sequences and all) goes nowhere.
TEST_F(CommandIntakeTest, AClientIdTooLongOrNotPrintableIsRejectedAndEchoedPrintable) {
  std::vector<ack_t> answers;
  bus_.Subscribe(channels_.ack, [&answers](const std::string&, const uint8_t* data, size_t size) {
    std::string error;
    if (auto ack = wire::CheckedDecode<ack_t>(data, size, 1 << 16, &error)) answers.push_back(*ack);
  });
  wind_command_t command = testing::SomeWindCommand();
  const std::string longest(CommandIntake::kMaxClientIdLength, 'c');
  for (const std::string& id : {longest + "c", "\x1b[2J" + std::string(60000, 'c'), std::string("tab\there"),
                                std::string("space here"), std::string("del\x7f")}) {
    command.client_id = id;
    bus_.Publish(channels_.wind, command);
    bus_.HandleAll();
  }
  ASSERT_EQ(answers.size(), 5u);
  EXPECT_EQ(answers[0].reason, "client_id: 65 characters; allowed 1 .. 64");
  EXPECT_EQ(answers[0].client_id, longest + "...");
  EXPECT_EQ(answers[1].reason, "client_id: 60004 characters; allowed 1 .. 64");
  EXPECT_EQ(answers[1].client_id, "\\x1b[2J" + std::string(57, 'c') + "...");
  EXPECT_EQ(answers[2].client_id, "tab\\x09here");
  EXPECT_EQ(answers[4].client_id, "del\\x7f");
  for (size_t k = 2; k < answers.size(); ++k)
    EXPECT_EQ(answers[k].reason, "client_id: allowed printable ASCII without spaces") << answers[k].client_id;
  for (const ack_t& answer : answers) EXPECT_FALSE(answer.accepted);
  EXPECT_EQ(stats().commands_rejected, 5);
  EXPECT_EQ(scene().wind.velocity, Scene{}.wind.velocity);
  command.client_id = longest;  // 64 printable characters are an id
  bus_.Publish(channels_.wind, command);
  bus_.HandleAll();
  EXPECT_EQ(stats().commands_accepted, 1);
}

TEST_F(CommandIntakeTest, HostileBytesOnEveryCommandChannelAreCountedAndDropped) {
  std::mt19937 random(3);
  const std::vector<uint8_t> valid = testing::Encode(testing::SomeParamCommand());
  std::vector<std::vector<uint8_t>> hostile = {
      {},                                                    // empty
      {1, 2, 3},                                             // shorter than a fingerprint
      std::vector<uint8_t>(valid.begin(), valid.end() - 3),  // truncated
      std::vector<uint8_t>(70 * 1024, 0xab),                 // oversized
      testing::Encode(testing::SomeState()),                 // another type's fingerprint
  };
  std::vector<uint8_t> huge_count = valid;  // num_assignments = 2^31 - 1
  const size_t at = 8 + 8 + 4 + 12 + 8 + 1;
  huge_count[at] = 0x7f;
  huge_count[at + 1] = huge_count[at + 2] = huge_count[at + 3] = 0xff;
  hostile.push_back(huge_count);
  for (int i = 0; i < 50; ++i) {  // random bytes, some behind a real fingerprint
    std::vector<uint8_t> bytes(1 + random() % 200);
    for (uint8_t& b : bytes) b = static_cast<uint8_t>(random());
    if (i % 2 == 0 && bytes.size() >= 8) std::copy(valid.begin(), valid.begin() + 8, bytes.begin());
    hostile.push_back(bytes);
  }
  const auto before = Values();
  int64_t sent = 0;
  for (const std::string& channel :
       {channels_.wind, channels_.param, channels_.refresh, channels_.camera, channels_.keyframe}) {
    for (const auto& bytes : hostile) {
      bus_.Publish(channel, bytes.data(), bytes.size());
      bus_.HandleAll();
      ++sent;
    }
  }
  EXPECT_EQ(stats().messages_dropped, sent);
  EXPECT_EQ(stats().commands_accepted, 0);
  EXPECT_EQ(Values(), before);
  // And the server still answers.
  EXPECT_EQ(client_.Send(channels_.wind, testing::SomeWindCommand()).result, CommandOutcome::kAccepted);
}

TEST_F(CommandIntakeTest, CameraMovesAreValidatedAndApplied) {
  camera_command_t command{};
  command.operation = camera_command_t::ORBIT;
  command.angle = 0.5;
  const Eigen::Vector3d eye = server_.session().scene().camera.eye;
  EXPECT_EQ(client_.Send(channels_.camera, command).result, CommandOutcome::kAccepted);
  EXPECT_NE(server_.session().scene().camera.eye, eye);

  const Eigen::Vector3d moved = server_.session().scene().camera.eye;
  command.angle = std::numeric_limits<double>::quiet_NaN();
  const CommandOutcome outcome = client_.Send(channels_.camera, command);
  EXPECT_EQ(outcome.result, CommandOutcome::kRejected);
  EXPECT_EQ(outcome.reason.rfind("angle:", 0), 0u) << outcome.reason;
  EXPECT_EQ(server_.session().scene().camera.eye, moved);

  camera_command_t reset{};
  reset.operation = camera_command_t::RESET;
  EXPECT_EQ(client_.Send(channels_.camera, reset).result, CommandOutcome::kAccepted);
  EXPECT_EQ(server_.session().scene().camera.eye, eye);
}

TEST_F(CommandIntakeTest, ZoomEyeAndFieldOfViewAreAppliedOverTheBus) {
  const render::Camera& camera = server_.session().scene().camera;
  const double distance = (camera.eye - camera.target).norm();
  camera_command_t zoom{};
  zoom.operation = camera_command_t::ZOOM;
  zoom.factor = 2;
  CommandOutcome outcome = client_.Send(channels_.camera, zoom);
  EXPECT_EQ(outcome.result, CommandOutcome::kAccepted) << outcome.reason;
  EXPECT_NEAR((camera.eye - camera.target).norm(), distance / 2, 1e-12);

  camera_command_t eye{};
  eye.operation = camera_command_t::SET_EYE;
  eye.vector[0] = 1;
  eye.vector[1] = 1.5;
  eye.vector[2] = 3;
  outcome = client_.Send(channels_.camera, eye);
  EXPECT_EQ(outcome.result, CommandOutcome::kAccepted) << outcome.reason;
  EXPECT_EQ(camera.eye, Eigen::Vector3d(1, 1.5, 3));
  eye.vector[1] = -2;  // under the ground
  outcome = client_.Send(channels_.camera, eye);
  EXPECT_EQ(outcome.result, CommandOutcome::kRejected);
  EXPECT_EQ(outcome.reason.rfind("vector: the eye would be at y = -2 m", 0), 0u) << outcome.reason;
  EXPECT_EQ(camera.eye, Eigen::Vector3d(1, 1.5, 3));

  camera_command_t fov{};
  fov.operation = camera_command_t::SET_FOV;
  fov.angle = 50 * M_PI / 180;
  outcome = client_.Send(channels_.camera, fov);
  EXPECT_EQ(outcome.result, CommandOutcome::kAccepted) << outcome.reason;
  EXPECT_EQ(camera.fov_y, fov.angle);
  fov.angle = 150 * M_PI / 180;
  outcome = client_.Send(channels_.camera, fov);
  EXPECT_EQ(outcome.result, CommandOutcome::kRejected);
  EXPECT_EQ(outcome.reason.rfind("angle: 150 degrees is out of range; allowed 10 .. 120 degrees", 0), 0u)
      << outcome.reason;
  EXPECT_EQ(camera.fov_y, 50 * M_PI / 180);
  EXPECT_EQ(stats().commands_accepted, 3);
  EXPECT_EQ(stats().commands_rejected, 2);
}

TEST_F(CommandIntakeTest, RefreshRequestsAreAcknowledged) {
  EXPECT_EQ(client_.Send(channels_.refresh, refresh_request_t{}).result, CommandOutcome::kAccepted);
}

// The request id is a sequence, 0 and up: a negative one is rejected and asks for nothing (no
// keyframe, no checkpoint).
TEST_F(CommandIntakeTest, ARefreshWithANegativeSequenceIsRejected) {
  std::vector<ack_t> answers;
  int checkpoints = 0;
  bus_.Subscribe(channels_.ack, [&answers](const std::string&, const uint8_t* data, size_t size) {
    std::string error;
    if (auto ack = wire::CheckedDecode<ack_t>(data, size, 1 << 16, &error)) answers.push_back(*ack);
  });
  bus_.Subscribe(channels_.checkpoint, [&](const std::string&, const uint8_t*, size_t) { ++checkpoints; });
  clock_.Step(server_);  // the start's checkpoint
  checkpoints = 0;
  refresh_request_t request{};
  request.client_id = "viewer";
  request.sequence = -1;
  bus_.Publish(channels_.refresh, request);
  for (int step = 0; step < 8; ++step) clock_.Step(server_);
  ASSERT_EQ(answers.size(), 1u);
  EXPECT_FALSE(answers[0].accepted);
  EXPECT_EQ(answers[0].reason, "sequence: -1; allowed 0 and up");
  EXPECT_EQ(checkpoints, 0);
  EXPECT_EQ(stats().commands_rejected, 1);
}

// At most 64 assignments in one PARAM, however valid each is; the whole is refused.
TEST_F(CommandIntakeTest, AParamOfMoreThan64AssignmentsIsRejected) {
  const auto before = Values();
  const size_t most = Session::kMaxAssignments;
  CommandOutcome outcome =
      SetParams(std::vector<std::string>(most + 1, "damping"), std::vector<std::string>(most + 1, "0.1"));
  EXPECT_EQ(outcome.result, CommandOutcome::kRejected);
  EXPECT_EQ(outcome.reason, "num_assignments: 65 is out of range; allowed 0 .. 64");
  EXPECT_EQ(Values(), before);
  outcome = SetParams(std::vector<std::string>(most, "damping"), std::vector<std::string>(most, "0.1"));
  EXPECT_EQ(outcome.result, CommandOutcome::kAccepted) << outcome.reason;
  EXPECT_EQ(scene().sim.forces.damping, 0.1);
}

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
