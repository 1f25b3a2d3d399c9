// flagd's own record of its inputs: a server on an in-process bus takes commands while it writes
// the log, and `flagd replay`'s engine steps the log again to the same hashes; a server resumed
// from the log of one killed mid-session steps on as the original did; a log that cannot be
// written ends, and the server and the bus go on.
#include "server/service/inputs_log.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <map>
#include <string>

#include "client/command_client.hpp"
#include "messages/event_log_reader.hpp"
#include "server/service/replay.hpp"
#include "server/service/resume_point.hpp"
#include "server/service/server.hpp"
#include "tests/messages/message_fixtures.hpp"
#include "tests/service/log_fixtures.hpp"
#include "tests/service/simulated_clock.hpp"

namespace flagsim {
namespace {

Scene SmallWithoutFrames() {
  Scene scene = testing::SmallVerletScene();
  scene.service.frame_rate = 0;
  return scene;
}

/// Counts what reaches the bus, by channel.
class CountingBus final : public Publisher {
 public:
  using Publisher::Publish;
  void Publish(const std::string& channel, const uint8_t*, size_t) override { ++messages[channel]; }
  std::map<std::string, int> messages;
};

TEST(InputsLog, AServersOwnRecordReplaysBitForBit) {
  const std::string path = testing::TempPath("inputs.lcmlog");
  const Channels channels;
  Bus bus("memq://");
  testing::SimulatedClock clock;
  ServerOptions options = clock.ServerOnIt();
  options.duration = 11;  // 5500 steps: past the periodic checkpoints at 2500 and 5000
  options.inputs_log = path;
  Server server(bus, channels, SmallWithoutFrames(), options);
  CommandClient client(bus, channels, 5.0, {}, clock.Reader());
  client.WhileWaiting([&] { clock.Step(server); });
  wind_command_t wind = testing::SomeWindCommand();
  ASSERT_EQ(client.Send(channels.wind, wind).result, CommandOutcome::kAccepted);
  param_command_t stiffer{};
  stiffer.names = {"stiffness"};
  stiffer.values = {"3500"};
  stiffer.num_assignments = 1;
  ASSERT_EQ(client.Send(channels.param, stiffer).result, CommandOutcome::kAccepted);
  clock.StepUntil(server, [&] { return server.session().simulation().state().time >= options.duration; });
  const std::atomic<bool> stop{false};
  server.Run(stop);  // at its duration: the end checkpoint, and the log closed
  const int64_t last_step = server.session().simulation().state().step;
  ASSERT_EQ(last_step, 5500);

  for (const int threads : {1, 2}) {
    ReplayOptions replay;
    replay.threads = threads;
    const ReplayReport report = Replay(path, replay);
    EXPECT_TRUE(report.ok()) << report.error << report.divergence;
    EXPECT_EQ(report.first_step, 0);
    EXPECT_EQ(report.first_reason, "start");
    EXPECT_EQ(report.commands, 2);
    EXPECT_EQ(report.checkpoints_checked, 3);  // at 2500, at 5000 and at the end
    EXPECT_EQ(report.states_checked, 0);       // inputs only: no STATE in this log
    EXPECT_EQ(report.last_step, last_step);
    EXPECT_EQ(report.log_end, "");
  }
  std::remove(path.c_str());
}

/// The log at `path` without its last event, as a server killed before it wrote it leaves it.
void DropLastEvent(const std::string& path) {
  EventLogReader reader(path);
  LogEvent event;
  uint64_t last = 0;
  while (reader.Next(&event, [](const std::string&) { return false; })) last = event.offset;
  ASSERT_EQ(truncate(path.c_str(), off_t(last)), 0);
}

// The original runs to its end (step 5500); cut before its end checkpoint, its log resumes at
// the periodic one at 5000, and the resumed server, given the rest of the time, ends where the
// original did, bit for bit, with a record of its own that replays from its "resume" checkpoint.
TEST(InputsLog, AServerResumedFromItsRecordStepsOnAsTheOriginal) {
  const std::string original_log = testing::TempPath("original.lcmlog");
  const std::string resumed_log = testing::TempPath("resumed.lcmlog");
  const Channels channels;
  Bus bus("memq://");
  const std::atomic<bool> stop{false};
  testing::SimulatedClock clock;
  ServerOptions options = clock.ServerOnIt();
  options.duration = 11;
  options.inputs_log = original_log;
  Server original(bus, channels, SmallWithoutFrames(), options);
  CommandClient client(bus, channels, 5.0, {}, clock.Reader());
  client.WhileWaiting([&] { clock.Step(original); });
  ASSERT_EQ(client.Send(channels.wind, testing::SomeWindCommand()).result, CommandOutcome::kAccepted);
  clock.StepUntil(original, [&] { return original.session().simulation().state().time >= options.duration; });
  original.Run(stop);  // at its duration: the end checkpoint, and the log closed
  const auto& end = original.session().simulation().state();
  ASSERT_EQ(end.step, 5500);
  DropLastEvent(original_log);

  const ResumePoint point = FindResumePoint(original_log, channels.prefix);
  ASSERT_EQ(point.error, "");
  ASSERT_EQ(point.step, 5000);
  ServerOptions rest;
  rest.fast = true;
  rest.duration = end.time - point.sim_time - SmallWithoutFrames().sim.dt / 2;  // to step 5500
  rest.inputs_log = resumed_log;
  Bus own_bus("memq://");  // the original's last messages are not another server's
  Server resumed(own_bus, channels, point.snapshot, rest);
  EXPECT_EQ(resumed.session().simulation().Hash(), point.state_hash);
  resumed.Run(stop);
  EXPECT_EQ(resumed.session().simulation().state().step, 5500);
  EXPECT_EQ(resumed.session().simulation().Hash(), original.session().simulation().Hash());

  const ReplayReport report = Replay(resumed_log, {});
  EXPECT_TRUE(report.ok()) << report.error << report.divergence;
  EXPECT_EQ(report.first_reason, "resume");
  EXPECT_EQ(report.first_step, 5000);
  EXPECT_EQ(report.first_hash, point.state_hash);
  EXPECT_EQ(report.last_checkpoint_step, 5500);  // the end, and no second checkpoint at 5000
  EXPECT_EQ(report.checkpoints_checked, 1);
  std::remove(original_log.c_str());
  std::remove(resumed_log.c_str());
}

TEST(InputsLog, AFailedWriteEndsTheLogAndNothingElse) {
  CountingBus bus;
  InputsLog log(bus, "/dev/full", 0);  // opens, and every write that reaches the disk fails
  const std::vector<uint8_t> bytes(64 << 10, 7);
  for (int i = 0; i < 8; ++i) {
    log.AdvanceTo(0.01 * i);
    log.Publish("CHECKPOINT", bytes.data(), bytes.size());
  }
  EXPECT_FALSE(log.Close());
  EXPECT_EQ(bus.messages["CHECKPOINT"], 8);  // the bus had every one
}

TEST(InputsLog, AnUnwritablePathIsNamed) {
  CountingBus bus;
  try {
    InputsLog log(bus, "/nonexistent-dir/inputs.lcmlog", 0);
    FAIL() << "opened a log in a directory that does not exist";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("/nonexistent-dir/inputs.lcmlog"), std::string::npos)
        << error.what();
  }
}

}  // namespace
}  // namespace flagsim
