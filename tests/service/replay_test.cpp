// Replay against logs written here the way a live server writes them (the journal, STATE at
// each boundary, commands as they came): every hash equal when nothing differs, the first
// difference found when something does, a log recorded from mid-session, a log without a
// checkpoint, a log cut short.
#include "server/service/replay.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "messages/channels.hpp"
#include "server/service/command_apply.hpp"
#include "server/service/journal.hpp"
#include "server/service/log_publisher.hpp"
#include "server/service/message_builders.hpp"
#include "tests/service/log_fixtures.hpp"

namespace flagsim {
namespace {

using testing::TempPath;

constexpr int64_t kStart = 1700000000000000;  // us since the Unix epoch

template <class Message>
std::vector<uint8_t> Bytes(Message message) {
  message.client_id = "test";
  return Publisher::Encode(message);
}

/// What a live session would publish, into a log: the journal's checkpoints and commands, a
/// STATE after every step. The session takes a wind, a stiffer cloth and a keyframe request,
/// and runs past two periodic checkpoints. From step `record_from` on only (a recorder that
/// came late); a STATE whose step is `tamper_at` carries a wrong hash.
struct Recording {
  int64_t record_from = 0;
  int64_t tamper_at = -1;
  int64_t steps = 2 * Journal::kCheckpointSteps + 300;
};

void Record(const std::string& path, const Recording& recording) {
  const Channels channels;
  LogPublisher log(path, kStart);
  Session session(testing::SmallVerletScene());
  Journal journal(&log, channels);
  wind_command_t wind{};
  wind.velocity[0] = 9;
  wind.velocity[2] = 3;
  wind.ramp_time = 0.3;
  param_command_t param{};
  param.names = {"stiffness"};
  param.values = {"3500"};
  param.num_assignments = 1;
  const auto command = [&](const std::string& channel, const std::vector<uint8_t>& bytes) {
    ASSERT_EQ(ApplyCommandBytes(channels.Unprefixed(channel), bytes, &session), "");
    if (session.simulation().state().step >= recording.record_from)
      journal.Applied(session, channel, bytes.data(), bytes.size(), {"replay-test", ""}, log.utime());
  };
  for (int64_t step = 0; step < recording.steps; ++step) {
    log.AdvanceTo(session.simulation().state().time);
    const bool recorded = step >= recording.record_from;
    if (recorded) journal.AtBoundary(session, log.utime());
    if (step == 300) command(channels.wind, Bytes(wind));
    if (step == 900) command(channels.param, Bytes(param));
    if (step == recording.record_from && step > 0) journal.Refresh(session, log.utime());
    session.Step();
    state_t state = MakeStateMessage(session, log.utime());
    if (state.step == recording.tamper_at) state.state_hash ^= 1;
    if (session.simulation().state().step >= recording.record_from) log.Publish(channels.state, state);
  }
  log.Close();
}

TEST(Replay, EveryHashEqualAtOneAndTwoThreads) {
  const std::string path = TempPath("whole.lcmlog");
  Recording recording;
  Record(path, recording);
  for (const int threads : {1, 2}) {
    ReplayOptions options;
    options.threads = threads;
    const ReplayReport report = Replay(path, options);
    EXPECT_TRUE(report.ok()) << report.error << report.divergence;
    EXPECT_EQ(report.first_step, 0);
    EXPECT_EQ(report.first_reason, "start");
    EXPECT_EQ(report.last_step, recording.steps);
    EXPECT_EQ(report.threads, threads);
    EXPECT_EQ(report.commands, 2);
    EXPECT_EQ(report.states_checked, recording.steps);
    EXPECT_EQ(report.checkpoints_checked, 2);  // the periodic ones after the start
    EXPECT_EQ(report.last_checkpoint_step, 2 * Journal::kCheckpointSteps);
    EXPECT_EQ(report.log_end, "");
  }
  std::remove(path.c_str());
}

TEST(Replay, TheFirstDifferenceIsFoundAndNamed) {
  const std::string path = TempPath("tampered.lcmlog");
  Recording recording;
  recording.tamper_at = 1234;
  Record(path, recording);
  const ReplayReport report = Replay(path, {});
  EXPECT_FALSE(report.ok());
  EXPECT_EQ(report.divergence_step, 1234);
  EXPECT_NE(report.divergence.find("state hash at step 1234"), std::string::npos) << report.divergence;
  EXPECT_EQ(report.states_checked, 1234);
  std::remove(path.c_str());
}

TEST(Replay, ALogFromMidSessionResumesAtItsFirstCheckpoint) {
  const std::string path = TempPath("late.lcmlog");
  Recording recording;
  recording.record_from = 1500;  // after the wind and the parameters: both are in the checkpoint
  Record(path, recording);
  const ReplayReport report = Replay(path, {});
  EXPECT_TRUE(report.ok()) << report.error << report.divergence;
  EXPECT_EQ(report.first_step, 1500);
  EXPECT_EQ(report.first_reason, "refresh");
  EXPECT_EQ(report.states_checked, recording.steps - 1500);
  std::remove(path.c_str());
}

TEST(Replay, ACutLogReplaysUpToItsLastWholeEvent) {
  const std::string path = TempPath("cut.lcmlog");
  Record(path, Recording{});
  std::ifstream in(path, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(bytes.data(), std::streamsize(bytes.size() / 2 + 5));
  const ReplayReport report = Replay(path, {});
  EXPECT_TRUE(report.ok()) << report.error << report.divergence;
  EXPECT_NE(report.log_end.find("cut short"), std::string::npos) << report.log_end;
  EXPECT_GT(report.states_checked, 1000);
  std::remove(path.c_str());
}

TEST(Replay, AnEventFarPastTheReplayEndsItAsADamagedLog) {
  // A STATE whose step number was damaged: the replay does not step a billion steps to reach it.
  const std::string path = TempPath("far.lcmlog");
  {
    const Channels channels;
    LogPublisher log(path, kStart);
    Session session(testing::SmallVerletScene());
    Journal(&log, channels).AtBoundary(session, log.utime());
    session.Step();
    state_t state = MakeStateMessage(session, log.utime());
    log.Publish(channels.state, state);
    state.step = 1'000'000'000;
    log.Publish(channels.state, state);
    log.Close();
  }
  const ReplayReport report = Replay(path, {});
  EXPECT_TRUE(report.ok()) << report.error << report.divergence;
  EXPECT_EQ(report.states_checked, 1);
  EXPECT_EQ(report.last_step, 1);
  EXPECT_NE(report.log_end.find("FLAGSIM_STATE at step 1000000000"), std::string::npos) << report.log_end;
  EXPECT_NE(report.log_end.find("damaged"), std::string::npos) << report.log_end;
  std::remove(path.c_str());
}

TEST(Replay, AFileThatIsNotALogSaysSo) {
  const std::string path = TempPath("notalog.lcmlog");
  std::ofstream(path) << "name = \"gale\"\n";
  const std::string error = Replay(path, {}).error;
  EXPECT_EQ(error.rfind(path + ": at byte 0, event 0: not an LCM event log", 0), 0u) << error;
  EXPECT_NE(error.find("; no whole CHECKPOINT on FLAGSIM_CHECKPOINT before it"), std::string::npos) << error;
  std::remove(path.c_str());
}

TEST(Replay, NothingToReplayIsSaid) {
  const std::string path = TempPath("whole2.lcmlog");
  Record(path, Recording{0, -1, 100});
  ReplayOptions other;
  other.prefix = "OTHER_";
  EXPECT_NE(Replay(path, other).error.find("no whole CHECKPOINT on OTHER_CHECKPOINT"), std::string::npos);
  EXPECT_NE(Replay(TempPath("missing.lcmlog"), {}).error.find("missing.lcmlog"), std::string::npos);
  std::remove(path.c_str());
}

}  // namespace
}  // namespace flagsim
