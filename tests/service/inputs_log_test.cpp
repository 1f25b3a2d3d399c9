// flagd's own record of its inputs: a server on an in-process bus takes commands while it writes
// the log, and `flagd replay`'s engine steps the log again to the same hashes; a log that cannot
// be written ends, and the server and the bus go on.
#include "server/service/inputs_log.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cstdio>
#include <map>
#include <string>

#include "client/command_client.hpp"
#include "server/service/replay.hpp"
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
