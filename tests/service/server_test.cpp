// The server's loop on a simulated clock (memq://): it steps as far as the clock has moved, draws
// every frame that falls due or counts it skipped, and answers a REFRESH with a keyframe.
#include "server/service/server.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>

#include "client/command_client.hpp"
#include "flagsim/frame_t.hpp"
#include "flagsim/refresh_request_t.hpp"

namespace flagsim {
namespace {

constexpr double kDt = 1.0 / 512;  ///< s: steps and frame times land exactly on binary fractions

class ServerTest : public ::testing::Test {
 protected:
  ServerTest() : bus_("memq://") {
    scene_.sim.dt = kDt;
    scene_.sim.cols = 16;
    scene_.sim.rows = 12;
    scene_.service.frame_rate = 32;  // a frame every 16 steps
    scene_.camera.width = 128;
    scene_.camera.height = 96;
    options_.clock = [this] { return now_; };
    bus_.Subscribe(channels_.frame, [this](const std::string&, const uint8_t* data, size_t size) {
      manifests_.emplace_back().decode(data, 0, int(size));
    });
  }

  int64_t steps(const Server& server) const { return server.session().simulation().state().step; }

  /// Handles the bus until `done`, for at most 10 s of wall time: the frame stage and the paced
  /// publisher are real threads.
  template <typename Done>
  bool HandleUntil(const Done& done) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (!done() && std::chrono::steady_clock::now() < until) {
      bus_.Handle(1);
    }
    return done();
  }

  Bus bus_;
  Channels channels_;
  Scene scene_;
  ServerOptions options_;
  double now_ = 0;  ///< s, the server's clock
  std::vector<frame_t> manifests_;
};

TEST_F(ServerTest, StepsAsFarAsTheClockHasMoved) {
  Server server(bus_, channels_, scene_, options_);
  server.Tick(now_);
  EXPECT_EQ(steps(server), 0);
  now_ = 16 * kDt;
  server.Tick(now_);
  EXPECT_EQ(steps(server), 16);
  now_ += kDt / 2;  // half a step owed: not yet
  server.Tick(now_);
  EXPECT_EQ(steps(server), 16);
  now_ += kDt / 2;
  server.Tick(now_);
  EXPECT_EQ(steps(server), 17);
  // A loop held up for 10 s steps no more than kMaxCatchUp's worth, rather than spiral.
  now_ += 10;
  server.Tick(now_);
  EXPECT_EQ(steps(server), 17 + int64_t(Server::kMaxCatchUp / kDt));
}

TEST_F(ServerTest, EveryFrameDueIsDrawnOrCountedSkipped) {
  Server server(bus_, channels_, scene_, options_);
  server.Tick(now_);
  for (int tick = 1; tick < 64; ++tick) {  // 8 steps a tick, short of the first STATUS at 1 s
    now_ = tick / 64.0;
    server.Tick(now_);
    server.DrainFrames();
  }
  ASSERT_EQ(steps(server), 504);
  // Due after step 1 (time 0 has passed) and at every 16th step: 32.
  EXPECT_EQ(server.stats().frames_published + server.stats().frames_skipped, 32);
  EXPECT_GE(server.stats().frames_published, 1);
  const int64_t published = server.stats().frames_published;
  ASSERT_TRUE(HandleUntil([&] { return int64_t(manifests_.size()) == published; }));
  EXPECT_TRUE(manifests_.front().keyframe);
}

TEST_F(ServerTest, ARefreshIsAnsweredByAKeyframeThatNamesIt) {
  scene_.service.frame_rate = 0;  // no frames but the one asked for
  Server server(bus_, channels_, scene_, options_);
  CommandClient client(bus_, channels_, 5.0);
  client.WhileWaiting([&] {
    now_ += kDt;
    server.Tick(now_);
  });
  refresh_request_t request{};
  const CommandOutcome outcome = client.Send(channels_.refresh, request);
  ASSERT_EQ(outcome.result, CommandOutcome::kAccepted) << outcome.reason;
  server.Tick(now_);  // the frame goes to the stage at once, whatever the frame rate
  server.DrainFrames();
  ASSERT_TRUE(HandleUntil([&] { return !manifests_.empty(); }));
  ASSERT_EQ(manifests_.size(), 1u);
  EXPECT_TRUE(manifests_.front().keyframe);
  EXPECT_GE(manifests_.front().request_id, 0);
}

}  // namespace
}  // namespace flagsim
