// Where a killed server resumes, against logs written here the way `flagd --record-inputs`
// writes them (the journal's checkpoints and commands, STATUS now and then) and then cut off as
// a kill leaves them: the last sound checkpoint, its state bit for bit, and what came after it
// counted as lost; a checkpoint cut mid-event leaves the one before; no checkpoint is said.
#include "server/service/resume_point.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

#include "flagsim/status_t.hpp"
#include "messages/channels.hpp"
#include "server/service/checkpoint_codec.hpp"
#include "server/service/command_apply.hpp"
#include "server/service/journal.hpp"
#include "server/service/log_publisher.hpp"
#include "tests/service/log_fixtures.hpp"

namespace flagsim {
namespace {

using testing::TempPath;

constexpr int64_t kStart = 1700000000000000;  // us since the Unix epoch

/// A server's inputs log up to step `steps`, where it was killed (no end checkpoint unless
/// `end`): periodic checkpoints at 0, 2500 and 5000; a wind at 300 and 5100, a stiffness at 2600
/// and 5200, a STATUS every 250 steps, and one more command at `steps - 10`. What the session
/// was at each step is kept: its hash and simulated time.
struct KilledServer {
  int64_t steps = 5400;
  bool end = false;
  std::map<int64_t, uint64_t> hashes;  ///< by step
  std::map<int64_t, double> times;     ///< s, simulated, by step
};

void Record(const std::string& path, KilledServer* server) {
  const Channels channels;
  LogPublisher log(path, kStart);
  Session session(testing::SmallVerletScene());
  Journal journal(&log, channels);
  wind_command_t wind{};
  wind.velocity[0] = 7;
  param_command_t param{};
  param.names = {"stiffness"};
  param.values = {"3000"};
  param.num_assignments = 1;
  const auto command = [&](const std::string& channel, std::vector<uint8_t> bytes) {
    ASSERT_EQ(ApplyCommandBytes(channels.Unprefixed(channel), bytes, &session), "");
    journal.Applied(session, channel, bytes.data(), bytes.size(), {"resume-test", ""}, log.utime());
  };
  const std::map<int64_t, std::string> commands = {{300, channels.wind},
                                                   {2600, channels.param},
                                                   {5100, channels.wind},
                                                   {5200, channels.param},
                                                   {server->steps - 10, channels.wind}};
  for (int64_t step = 0;; ++step) {
    log.AdvanceTo(session.simulation().state().time);
    server->hashes[step] = session.simulation().Hash();
    server->times[step] = session.simulation().state().time;
    journal.AtBoundary(session, log.utime());
    if (step % 250 == 0) {
      status_t status{};
      status.step = step;
      status.sim_time = session.simulation().state().time;
      log.Publish(channels.status, status);
    }
    if (const auto found = commands.find(step); found != commands.end()) {
      wind.velocity[2] = double(step) / 1000;  // each a change
      found->second == channels.wind ? command(found->second, Publisher::Encode(wind))
                                     : command(found->second, Publisher::Encode(param));
    }
    if (step == server->steps) break;
    session.Step();
  }
  if (server->end) journal.End(session, log.utime());
  log.Close();
}

std::string ReadBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

TEST(ResumePoint, TheLastCheckpointAndWhatCameAfterIt) {
  const std::string path = TempPath("killed.lcmlog");
  KilledServer server;
  Record(path, &server);
  const ResumePoint point = FindResumePoint(path, Channels::kDefaultPrefix);
  ASSERT_EQ(point.error, "");
  EXPECT_EQ(point.step, 5000);
  EXPECT_EQ(point.reason, "periodic");
  EXPECT_EQ(point.sim_time, server.times[5000]);
  EXPECT_EQ(point.state_hash, server.hashes[5000]);
  EXPECT_EQ(Session(point.snapshot).simulation().Hash(), server.hashes[5000]) << "the state, bit for bit";
  EXPECT_EQ(point.commands_lost, 3);  // at 5100, 5200 and 5390
  // The last STATUS (5250) gives the time; the command after it (5390) adds its steps' worth.
  EXPECT_EQ(point.last_step, 5390);
  EXPECT_NEAR(point.last_time, server.times[5390], 1e-9);
  EXPECT_NEAR(point.lost_seconds(), server.times[5390] - server.times[5000], 1e-9);
  EXPECT_EQ(point.log_end, "");
  std::remove(path.c_str());
}

TEST(ResumePoint, AServerThatStoppedLosesNothing) {
  const std::string path = TempPath("stopped.lcmlog");
  KilledServer server;
  server.end = true;
  Record(path, &server);
  const ResumePoint point = FindResumePoint(path, Channels::kDefaultPrefix);
  ASSERT_EQ(point.error, "");
  EXPECT_EQ(point.reason, "end");
  EXPECT_EQ(point.step, server.steps);
  EXPECT_EQ(point.state_hash, server.hashes[server.steps]);
  EXPECT_EQ(point.commands_lost, 0);
  EXPECT_EQ(point.lost_seconds(), 0);
  std::remove(path.c_str());
}

// Killed while it wrote its end checkpoint: the one before it stands, and the cut is named.
TEST(ResumePoint, ACheckpointCutMidEventLeavesTheOneBefore) {
  const std::string path = TempPath("cut.lcmlog");
  KilledServer server;
  server.end = true;
  Record(path, &server);
  const std::string bytes = ReadBytes(path);
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(bytes.data(), std::streamsize(bytes.size() - 100));
  const ResumePoint point = FindResumePoint(path, Channels::kDefaultPrefix);
  ASSERT_EQ(point.error, "");
  EXPECT_EQ(point.step, 5000);
  EXPECT_EQ(point.commands_lost, 3);
  EXPECT_NE(point.log_end.find("cut short"), std::string::npos) << point.log_end;
  EXPECT_NE(DescribeResume(point).find("(the log stops early: " + path + ": at byte "), std::string::npos)
      << DescribeResume(point);
  std::remove(path.c_str());
}

TEST(ResumePoint, SaysWhatIsLost) {
  ResumePoint point;
  point.reason = "periodic";
  point.step = 5000;
  point.sim_time = 10;
  point.last_step = 5867;
  point.last_time = 11.734;
  point.commands_lost = 2;
  EXPECT_EQ(DescribeResume(point),
            "the periodic checkpoint at step 5000 (t = 10.000 s); after it the log goes on to step 5867 "
            "(t = 11.734 s): 1.734 simulated seconds and 2 command(s) are lost");
}

// A file that is not a log says so, in the reader's own words, before it says that no checkpoint
// came.
TEST(ResumePoint, AFileThatIsNotALogSaysSo) {
  const std::string path = TempPath("notalog.lcmlog");
  std::ofstream(path) << "name = \"gale\"\n";
  const std::string error = FindResumePoint(path, Channels::kDefaultPrefix).error;
  EXPECT_EQ(error.rfind(path + ": at byte 0, event 0: not an LCM event log", 0), 0u) << error;
  EXPECT_NE(error.find("; no whole CHECKPOINT on FLAGSIM_CHECKPOINT before it to resume from"),
            std::string::npos)
      << error;
  std::remove(path.c_str());
}

// A checkpoint the codec refuses, or that does not decode, is passed over for the one before,
// and counted and named: where there is none before, in the error; else in what the resume says.
TEST(ResumePoint, RefusedCheckpointsAreCountedAndNamed) {
  const std::string path = TempPath("refused.lcmlog");
  const Channels channels;
  Session session(testing::SmallVerletScene());
  checkpoint_t refused = MakeCheckpointMessage(session.Snapshot(), "start", kStart);
  refused.substeps = 65536;
  const auto write = [&](bool sound_first) {
    LogPublisher log(path, kStart);
    if (sound_first)
      log.Publish(channels.checkpoint, MakeCheckpointMessage(session.Snapshot(), "start", kStart));
    const uint8_t garbage[] = {1, 2, 3};
    log.Publish(channels.checkpoint, garbage, sizeof(garbage));
    log.Publish(channels.checkpoint, refused);
    log.Close();
  };
  write(false);
  const std::string error = FindResumePoint(path, Channels::kDefaultPrefix).error;
  EXPECT_NE(
      error.find(
          "; 2 CHECKPOINT(s) refused, the last: checkpoint at step 0: substeps: 65536; allowed 1 .. 4096"),
      std::string::npos)
      << error;
  write(true);
  const ResumePoint point = FindResumePoint(path, Channels::kDefaultPrefix);
  ASSERT_EQ(point.error, "");
  EXPECT_EQ(point.reason, "start");
  EXPECT_EQ(point.checkpoints_refused, 2);
  EXPECT_NE(
      DescribeResume(point).find("; 2 later CHECKPOINT(s) refused, the last: checkpoint at step 0: substeps"),
      std::string::npos)
      << DescribeResume(point);
  std::remove(path.c_str());
}

TEST(ResumePoint, NothingToResumeFromIsSaid) {
  const std::string path = TempPath("other.lcmlog");
  KilledServer server;
  server.steps = 100;
  Record(path, &server);
  EXPECT_NE(FindResumePoint(path, "OTHER_").error.find("no whole CHECKPOINT on OTHER_CHECKPOINT"),
            std::string::npos);
  EXPECT_NE(FindResumePoint(TempPath("missing.lcmlog"), "FLAGSIM_").error.find("missing.lcmlog"),
            std::string::npos);
  std::remove(path.c_str());
}

}  // namespace
}  // namespace flagsim
