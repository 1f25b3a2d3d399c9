// The server's command side on an in-process bus (memq://): answers, validation, retries, and
// hostile bytes on every command channel. Keyframe commands: keyframe_commands_test.cpp.
#include "server/service/command_intake.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "tests/messages/message_fixtures.hpp"
#include "tests/service/command_intake_fixture.hpp"

namespace flagsim {
namespace {

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

}  // namespace
}  // namespace flagsim
