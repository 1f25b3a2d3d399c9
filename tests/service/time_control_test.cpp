// The simulation's clock under TIME and time_scale, on a simulated clock (memq://): a pause holds
// the state still while frames keep coming, a step takes exactly its steps and holds again,
// time_scale 0.5 runs half as many steps a second, a reset leaves the scale and says so, and a
// session with pauses, steps and scale changes replays bit for bit.
#include <gtest/gtest.h>

#include <atomic>
#include <memory>
#include <cstdio>
#include <string>

#include "client/command_client.hpp"
#include "flagsim/frame_t.hpp"
#include "flagsim/state_t.hpp"
#include "flagsim/time_command_t.hpp"
#include "server/service/message_builders.hpp"
#include "server/service/replay.hpp"
#include "server/service/server.hpp"
#include "tests/service/log_fixtures.hpp"
#include "tests/service/simulated_clock.hpp"

namespace flagsim {
namespace {

constexpr double kDt = 1.0 / 512;  ///< s: steps land exactly on binary fractions

class TimeControlTest : public ::testing::Test {
 protected:
  TimeControlTest() : bus_("memq://") {
    scene_.sim.dt = kDt;
    scene_.sim.cols = 16;
    scene_.sim.rows = 12;
    scene_.sim.threads = 1;
    scene_.service.frame_rate = 32;
    scene_.camera.width = 64;
    scene_.camera.height = 48;
    bus_.Subscribe(channels_.frame, [this](const std::string&, const uint8_t*, size_t) { ++frames_; });
    bus_.Subscribe(channels_.state, [this](const std::string&, const uint8_t* data, size_t size) {
      state_t state{};
      state.decode(data, 0, int(size));
      last_state_step_ = state.step;
    });
  }

  /// The server on the test's clock, and a client that moves the clock while it waits.
  void Start(ServerOptions options = {}) {
    const ServerOptions on_clock = clock_.ServerOnIt();
    options.clock = on_clock.clock;
    server_ = std::make_unique<Server>(bus_, channels_, scene_, options);
    server_->Tick(clock_.now());
    client_ = std::make_unique<CommandClient>(bus_, channels_, 5.0, CommandSigner{}, clock_.Reader());
    client_->WhileWaiting([this] { clock_.Step(*server_); });
  }

  CommandOutcome Time(int8_t operation, int32_t steps = 0) {
    time_command_t command{};
    command.operation = operation;
    command.steps = steps;
    return client_->Send(channels_.time, command);
  }
  CommandOutcome Set(const std::string& name, const std::string& value, bool reset = false) {
    param_command_t command{};
    command.reset_to_scene = reset;
    command.names = {name};
    command.values = {value};
    command.num_assignments = 1;
    return client_->Send(channels_.param, command);
  }

  /// Runs the loop for `seconds` of the clock, a step at a time, each frame drawn and sent
  /// before the clock moves on (the stage and the publisher are real threads).
  void Run(double seconds) {
    const double until = clock_.now() + seconds;
    while (clock_.now() < until - 1e-9) {
      clock_.Step(*server_);
      server_->DrainFrames();
      bus_.HandleAll();
    }
  }

  /// The frames of the client's wait sent and heard, before counting starts.
  void Settle() {
    server_->DrainFrames();
    bus_.HandleAll();
  }

  int64_t step() const { return server_->session().simulation().state().step; }
  uint64_t hash() const { return MakeStateMessage(server_->session(), 0).state_hash; }

  Bus bus_;
  Channels channels_;
  Scene scene_;
  testing::SimulatedClock clock_;
  std::unique_ptr<Server> server_;
  std::unique_ptr<CommandClient> client_;
  int frames_ = 0;  ///< FRAME manifests heard
  int64_t last_state_step_ = -1;  ///< of the last STATE heard
};

TEST_F(TimeControlTest, PauseHoldsTheStateStillWhileFramesKeepComing) {
  Start();
  Run(0.25);
  ASSERT_EQ(Time(time_command_t::PAUSE).result, CommandOutcome::kAccepted);
  Settle();
  const int64_t paused_at = step();
  const uint64_t paused_hash = hash();
  const int frames_before = frames_;
  const int64_t skipped_before = server_->stats().frames_skipped;
  Run(1.0);
  EXPECT_EQ(step(), paused_at);
  EXPECT_EQ(hash(), paused_hash);
  // 32 fall due on the clock in that second (within 1: the first falls due at once), and Run
  // waits for each to go out.
  const status_t status = MakeStatusMessage(server_->session(), server_->stats(), {}, 0);
  EXPECT_TRUE(status.paused);
  EXPECT_EQ(server_->stats().frames_skipped, skipped_before);
  EXPECT_NEAR(double(frames_ - frames_before), 32, 1);
  ASSERT_EQ(Time(time_command_t::RESUME).result, CommandOutcome::kAccepted);
  Run(0.25);
  EXPECT_GT(step(), paused_at);
}

TEST_F(TimeControlTest, StepTakesExactlyItsStepsAndHoldsAgain) {
  Start();
  ASSERT_EQ(Time(time_command_t::PAUSE).result, CommandOutcome::kAccepted);
  const CommandOutcome seven = Time(time_command_t::STEP, 7);
  ASSERT_EQ(seven.result, CommandOutcome::kAccepted);
  Run(0.5);
  EXPECT_EQ(step(), seven.step + 7);
  EXPECT_EQ(last_state_step_, seven.step + 7);  // a STATE says where the steps left the flag
  EXPECT_TRUE(server_->session().paused());
  EXPECT_EQ(server_->session().steps_owed(), 0);
  // From a running clock, a step pauses it after its steps.
  ASSERT_EQ(Time(time_command_t::RESUME).result, CommandOutcome::kAccepted);
  Run(0.25);
  const CommandOutcome three = Time(time_command_t::STEP, 3);
  ASSERT_EQ(three.result, CommandOutcome::kAccepted);
  Run(0.5);
  EXPECT_EQ(step(), three.step + 3);
  EXPECT_TRUE(server_->session().paused());

  const int64_t held = step();
  for (const int32_t steps : {0, -1, 100001}) {
    const CommandOutcome outcome = Time(time_command_t::STEP, steps);
    EXPECT_EQ(outcome.result, CommandOutcome::kRejected);
    EXPECT_EQ(outcome.reason, "steps: " + std::to_string(steps) + " is out of range; allowed 1 .. 100000");
  }
  const CommandOutcome unknown = Time(9);
  EXPECT_EQ(unknown.result, CommandOutcome::kRejected);
  EXPECT_EQ(unknown.reason, "operation: 9 is not an operation; allowed 1 (PAUSE), 2 (RESUME), 3 (STEP)");
  Run(0.25);
  EXPECT_EQ(step(), held);
}

TEST_F(TimeControlTest, HalfTheTimeScaleRunsHalfAsManyStepsASecond) {
  Start();
  Run(0.25);
  const int64_t at_one = step();
  Run(1.0);
  EXPECT_NEAR(double(step() - at_one), 512, 1);
  ASSERT_EQ(Set("time_scale", "0.5").result, CommandOutcome::kAccepted);
  Settle();
  const int64_t at_half = step();
  const int frames_before = frames_;
  const int64_t skipped_before = server_->stats().frames_skipped;
  Run(1.0);
  EXPECT_NEAR(double(step() - at_half), 256, 1);
  // On the clock: 32, not the 16 of half a simulated second.
  EXPECT_EQ(server_->stats().frames_skipped, skipped_before);
  EXPECT_NEAR(double(frames_ - frames_before), 32, 1);

  const CommandOutcome above = Set("time_scale", "5");
  EXPECT_EQ(above.result, CommandOutcome::kRejected);
  EXPECT_NE(above.reason.find("allowed 0.1 .. 4"), std::string::npos) << above.reason;
}

TEST_F(TimeControlTest, AResetLeavesTheScaleAndTheHoldAndSaysSo) {
  Start();
  ASSERT_EQ(Set("time_scale", "0.5").result, CommandOutcome::kAccepted);
  ASSERT_EQ(Time(time_command_t::PAUSE).result, CommandOutcome::kAccepted);
  const CommandOutcome reset = Set("mass", "0.4", true);
  ASSERT_EQ(reset.result, CommandOutcome::kAccepted) << reset.reason;
  EXPECT_EQ(reset.reason,
            "the simulation stays paused (flagctl time resume); time_scale stays 0.5 (a reset leaves it; "
            "flagctl time scale 1)");
  EXPECT_EQ(server_->session().scene().service.time_scale, 0.5);
  EXPECT_TRUE(server_->session().paused());
}

TEST_F(TimeControlTest, ASessionWithPausesStepsAndScalesReplaysBitForBit) {
  const std::string path = testing::TempPath("time_control.lcmlog");
  scene_.service.frame_rate = 0;
  ServerOptions options;
  options.duration = 3;
  options.inputs_log = path;
  Start(options);
  Run(0.25);
  ASSERT_EQ(Time(time_command_t::PAUSE).result, CommandOutcome::kAccepted);
  Run(0.25);
  ASSERT_EQ(Time(time_command_t::STEP, 5).result, CommandOutcome::kAccepted);
  Run(0.25);
  ASSERT_EQ(Set("time_scale", "2").result, CommandOutcome::kAccepted);
  ASSERT_EQ(Time(time_command_t::RESUME).result, CommandOutcome::kAccepted);
  Run(0.5);
  ASSERT_EQ(Set("time_scale", "0.25").result, CommandOutcome::kAccepted);
  Run(0.5);
  ASSERT_EQ(Set("time_scale", "1").result, CommandOutcome::kAccepted);
  ASSERT_TRUE(clock_.StepUntil(*server_, [&] { return server_->session().simulation().state().time >= 3; }));
  const std::atomic<bool> stop{false};
  server_->Run(stop);
  for (const int threads : {1, 2}) {
    ReplayOptions replay;
    replay.threads = threads;
    const ReplayReport report = Replay(path, replay);
    EXPECT_TRUE(report.ok()) << report.error << report.divergence;
    EXPECT_EQ(report.commands, 6);
    EXPECT_EQ(report.last_step, step());
  }
  std::remove(path.c_str());
}

}  // namespace
}  // namespace flagsim
