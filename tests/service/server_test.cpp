// The server's loop on a simulated clock (memq://): it steps as far as the clock has moved, draws
// every frame that falls due or counts it skipped, publishes at the steps a render of the scene
// does, and answers a REFRESH with a keyframe.
#include "server/service/server.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

#include "client/command_client.hpp"
#include "flagsim/frame_t.hpp"
#include "flagsim/refresh_request_t.hpp"
#include "flagsim/state_t.hpp"
#include "messages/checked_decode.hpp"
#include "messages/event_log_reader.hpp"
#include "server/service/offline_render.hpp"
#include "tests/messages/message_fixtures.hpp"

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
    bus_.Subscribe(channels_.state, [this](const std::string&, const uint8_t* data, size_t size) {
      state_t state{};
      state.decode(data, 0, int(size));
      state_steps_.push_back(state.step);
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
  std::vector<int64_t> state_steps_;  ///< of each STATE heard
};

/// The steps at which a render of `scene` over `steps` steps' boundaries publishes STATE and frames.
struct Published {
  std::vector<int64_t> states, frames;
};
Published RenderedSteps(const Scene& scene, int64_t steps, const Channels& channels) {
  const std::string path =
      std::string(::testing::TempDir()) + "/" + std::to_string(getpid()) + "_server.lcmlog";
  {
    LogPublisher log(path, 0);
    OfflineRender render(scene, double(steps + 1) * scene.sim.dt, channels, &log, nullptr);
    while (render.Advance()) {
    }
    log.Close();
  }
  Published published;
  EventLogReader reader(path);
  LogEvent event;
  std::string error;
  while (reader.Next(&event)) {
    const uint8_t* data = event.data.data();
    const size_t size = event.data.size();
    if (event.channel == channels.state)
      published.states.push_back(wire::CheckedDecode<state_t>(data, size, size, &error).value().step);
    if (event.channel == channels.frame)
      published.frames.push_back(wire::CheckedDecode<frame_t>(data, size, size, &error).value().step);
  }
  std::remove(path.c_str());
  return published;
}

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
  // Due at time 0 and at every 16th step: 32. The first went to the stage before the first
  // STATUS (at time 0 too), which began the window that frames_published counts.
  EXPECT_EQ(1 + server.stats().frames_published + server.stats().frames_skipped, 32);
  EXPECT_GE(server.stats().frames_published, 1);
  const int64_t published = 1 + server.stats().frames_published;
  ASSERT_TRUE(HandleUntil([&] { return int64_t(manifests_.size()) == published; }));
  EXPECT_TRUE(manifests_.front().keyframe);
}

// STATE goes out, and frames fall due, at the steps a render of the scene publishes them: which
// steps publish is the session's, not the clock's (BoundarySchedule).
TEST_F(ServerTest, PublishesAtTheStepsARenderDoes) {
  Server server(bus_, channels_, scene_, options_);
  server.Tick(now_);
  for (int tick = 1; tick < 64; ++tick) {
    now_ = tick / 64.0;
    server.Tick(now_);
    server.DrainFrames();
  }
  ASSERT_EQ(steps(server), 504);
  const int64_t published = 1 + server.stats().frames_published;  // as above
  ASSERT_TRUE(HandleUntil([&] { return int64_t(manifests_.size()) == published; }));
  const Published rendered = RenderedSteps(scene_, 504, channels_);
  ASSERT_EQ(rendered.frames.size(), 32u);
  EXPECT_EQ(rendered.frames.front(), 0);
  ASSERT_TRUE(HandleUntil([&] { return state_steps_.size() >= rendered.states.size(); }));
  EXPECT_EQ(state_steps_, rendered.states);
  for (const frame_t& manifest : manifests_) {  // those the stage drew; the others were skipped
    EXPECT_NE(std::find(rendered.frames.begin(), rendered.frames.end(), manifest.step), rendered.frames.end())
        << "a live frame at step " << manifest.step;
  }
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

// A client asking for the tables (flagctl params, status, keyframe list) sends a REFRESH: PARAMS,
// TIMELINE and the last second's STATUS come at once, not at the next second.
TEST_F(ServerTest, ARefreshPublishesTheTablesAtOnce) {
  scene_.service.frame_rate = 0;
  Server server(bus_, channels_, scene_, options_);
  int params = 0, statuses = 0, timelines = 0;
  const auto count = [this](const std::string& channel, int* counter) {
    bus_.Subscribe(channel, [counter](const std::string&, const uint8_t*, size_t) { ++*counter; });
  };
  count(channels_.params, &params);
  count(channels_.status, &statuses);
  count(channels_.timeline, &timelines);
  for (; now_ < 1.25; now_ += kDt) server.Tick(now_);  // past the first second's publications
  bus_.HandleAll();
  ASSERT_GE(statuses, 1);  // a last second's report to publish again
  params = statuses = timelines = 0;
  CommandClient client(bus_, channels_, 5.0);
  const double asked = now_;
  client.WhileWaiting([&] {
    now_ += kDt;
    server.Tick(now_);
  });
  ASSERT_EQ(client.Send(channels_.refresh, refresh_request_t{}).result, CommandOutcome::kAccepted);
  server.Tick(now_);
  bus_.HandleAll();
  EXPECT_LT(now_ - asked, 0.5);  // far from the next second
  EXPECT_EQ(params, 1);
  EXPECT_EQ(timelines, 1);
  EXPECT_EQ(statuses, 1);
}

// A reader's question (a tables-only REFRESH) gets the tables, not a checkpoint or a keyframe,
// and a burst of questions no more than kTablesPerSecond answers a second.
TEST_F(ServerTest, AQuestionGetsTheTablesAndNoMoreThanTenTimesASecond) {
  scene_.service.frame_rate = 0;
  Server server(bus_, channels_, scene_, options_);
  int params = 0, statuses = 0, checkpoints = 0;
  const auto count = [this](const std::string& channel, int* counter) {
    bus_.Subscribe(channel, [counter](const std::string&, const uint8_t*, size_t) { ++*counter; });
  };
  count(channels_.params, &params);
  count(channels_.status, &statuses);
  count(channels_.checkpoint, &checkpoints);
  for (; now_ < 1.25; now_ += kDt) server.Tick(now_);
  bus_.HandleAll();
  params = statuses = checkpoints = 0;
  refresh_request_t question{};
  question.tables_only = true;
  question.client_id = "reader";
  const double start = now_;
  for (int k = 0; k < 30; ++k) {  // 30 questions over 0.3 s of the clock
    question.sequence = k;
    const std::vector<uint8_t> bytes = testing::Encode(question);
    bus_.Publish(channels_.refresh, bytes.data(), bytes.size());
    for (int tick = 0; tick < 5; ++tick) server.Tick(now_ += 0.002);
  }
  bus_.HandleAll();
  ASSERT_LT(now_ - start, 0.75);  // no periodic publication in between
  EXPECT_EQ(params, 3);           // at 0, 0.1 and 0.2 s after the first
  EXPECT_EQ(statuses, 3);
  EXPECT_EQ(checkpoints, 0);
}

// Each keyframe request costs a CHECKPOINT, a full STATE and a keyframe: a flood of them over one
// second of the clock gets at most kKeyframesPerSecond answers, and the last request, sent
// between two of them, is still answered (it waits for its turn, it is not dropped).
TEST_F(ServerTest, AFloodOfKeyframeRequestsGetsTenAnswersASecondAndTheLastIsAnswered) {
  scene_.service.frame_rate = 0;  // no frames but those asked for
  Server server(bus_, channels_, scene_, options_);
  int checkpoints = 0;
  bus_.Subscribe(channels_.checkpoint, [&](const std::string&, const uint8_t*, size_t) { ++checkpoints; });
  server.Tick(now_);
  bus_.HandleAll();
  ASSERT_EQ(checkpoints, 1);  // the start's
  checkpoints = 0;
  refresh_request_t request{};
  constexpr int kRequests = 500;  // one every 2 ms for a second, each from its own viewer
  for (int k = 0; k < kRequests; ++k) {
    request.client_id = "viewer-" + std::to_string(k);
    request.sequence = k;
    const std::vector<uint8_t> bytes = testing::Encode(request);
    bus_.Publish(channels_.refresh, bytes.data(), bytes.size());
    server.Tick(now_ += 0.002);
    server.DrainFrames();
  }
  bus_.HandleAll();
  EXPECT_LE(checkpoints, int(Server::kKeyframesPerSecond));
  EXPECT_GE(checkpoints, 2);
  // The last request came 0.002 s before the flood's end: its turn comes within 0.1 s.
  const double flood_end = now_;
  while (now_ < flood_end + 0.12) {
    server.Tick(now_ += 0.002);
    server.DrainFrames();
  }
  // The stage and the paced publisher are threads of their own: the keyframe goes once they are free.
  const auto answered = [&] {
    return std::any_of(manifests_.begin(), manifests_.end(),
                       [&](const frame_t& manifest) { return manifest.request_id == kRequests - 1; });
  };
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (!answered() && std::chrono::steady_clock::now() < until) {
    server.Tick(now_);  // the clock stands: no new turn, only the frame that waits
    server.DrainFrames();
    bus_.Handle(1);
  }
  EXPECT_TRUE(answered());
  EXPECT_LE(checkpoints, int(Server::kKeyframesPerSecond) + 1);
  const auto keyframes = std::count_if(manifests_.begin(), manifests_.end(),
                                       [](const frame_t& manifest) { return manifest.request_id >= 0; });
  EXPECT_LE(keyframes, Server::kKeyframesPerSecond + 1);
}

}  // namespace
}  // namespace flagsim
