#include "server/service/offline_render.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "client/tile_assembler.hpp"
#include "flagsim/state_t.hpp"
#include "messages/checked_decode.hpp"
#include "messages/event_log_reader.hpp"

namespace flagsim {
namespace {

constexpr int64_t kStart = 1700000000000000;  // us since the Unix epoch

/// A small, quick scene: a coarse flag, a small image.
Scene SmallScene(double frame_rate) {
  Scene scene;
  scene.sim.cols = 8;
  scene.sim.rows = 6;
  scene.camera.width = 150;
  scene.camera.height = 90;
  scene.service.frame_rate = frame_rate;
  return scene;
}

struct Rendered {
  std::vector<LogEvent> events;
  std::vector<std::vector<uint8_t>> images;  ///< as the frame sink got them, by frame id
  OfflineRenderStats stats;
};

Rendered Render(const Scene& scene, double duration) {
  const std::string path =
      std::string(::testing::TempDir()) + "/" + std::to_string(getpid()) + "_render.lcmlog";
  Rendered rendered;
  {
    const Channels channels;
    LogPublisher log(path, kStart);
    OfflineRender render(scene, duration, channels, &log, [&](int64_t id, const render::Framebuffer& image) {
      EXPECT_EQ(id, int64_t(rendered.images.size()));
      rendered.images.push_back(image.rgb);
    });
    while (render.Advance()) {
    }
    EXPECT_TRUE(render.done());
    EXPECT_EQ(render.progress(), 1.0);
    log.Close();
    rendered.stats = render.stats();
  }
  EventLogReader reader(path);
  LogEvent event;
  while (reader.Next(&event)) rendered.events.push_back(event);
  EXPECT_EQ(reader.end(), EventLogReader::End::kClean);
  std::remove(path.c_str());
  return rendered;
}

template <class Message>
Message Decoded(const LogEvent& event) {
  std::string error;
  const auto message = wire::CheckedDecode<Message>(event.data.data(), event.data.size(), 1 << 24, &error);
  EXPECT_TRUE(message) << event.channel << ": " << error;
  return message.value_or(Message{});
}

TEST(OfflineRender, PublishesWhatALiveServerDoesOnSimulatedTime) {
  const double duration = 1.5, frame_rate = 8;
  const Scene scene = SmallScene(frame_rate);
  const Rendered rendered = Render(scene, duration);
  const Channels channels;
  // One frame each 1/frame_rate from 0 while t < duration; STATE likewise at its rate; PARAMS
  // each second.
  const int frames = int(std::ceil(duration * frame_rate));
  const int states = int(std::ceil(duration * scene.service.state_rate));
  const int params = int(std::ceil(duration));
  std::map<std::string, int> count;
  std::vector<frame_t> manifests;
  for (size_t i = 0; i < rendered.events.size(); ++i) {
    const LogEvent& event = rendered.events[i];
    ++count[event.channel];
    if (i > 0) {
      EXPECT_GE(event.timestamp, rendered.events[i - 1].timestamp) << "lcm-logplayer needs order";
    }
    if (event.channel == channels.frame) manifests.push_back(Decoded<frame_t>(event));
    if (event.channel == channels.state) {
      const state_t state = Decoded<state_t>(event);
      EXPECT_EQ(event.timestamp, kStart + std::llround(state.sim_time * 1e6));
      EXPECT_EQ(state.utime, event.timestamp);
      EXPECT_EQ(state.wind_gust, scene.wind.gust);
      EXPECT_EQ(state.kinetic_energy > 0, state.step > 0) << "at rest only at the start";
    }
  }
  EXPECT_EQ(count[channels.frame], frames);
  EXPECT_EQ(count[channels.state], states);
  EXPECT_EQ(count[channels.params], params);
  EXPECT_EQ(count[channels.tile], rendered.stats.tiles);
  EXPECT_EQ(int(rendered.images.size()), frames);
  ASSERT_EQ(int(manifests.size()), frames);
  EXPECT_TRUE(manifests[0].keyframe);
  for (int k = 0; k < frames; ++k) {
    EXPECT_EQ(manifests[k].frame_id, k);
    EXPECT_NEAR(manifests[k].sim_time, k / frame_rate, scene.sim.dt / 2 + 1e-9) << "frame " << k;
    EXPECT_EQ(manifests[k].keyframe, k == 0) << "frame " << k;  // the rolling refresh does the rest
    for (int i = 0; i < 3; ++i) {
      EXPECT_EQ(manifests[k].camera_eye[i], scene.camera.eye[i]);
      EXPECT_EQ(manifests[k].camera_target[i], scene.camera.target[i]);
    }
    EXPECT_NEAR(manifests[k].camera_fov, scene.camera.fov_y * 180 / M_PI, 1e-12);
  }
}

// Played through a client's assembler, the log gives back every frame the sink got, hash
// checked.
TEST(OfflineRender, TheLogAssemblesIntoTheFramesDrawn) {
  const Rendered rendered = Render(SmallScene(10), 1.0);
  const Channels channels;
  TileAssembler assembler;
  size_t frame = 0;
  for (const LogEvent& event : rendered.events) {
    if (event.channel == channels.tile) {
      EXPECT_EQ(assembler.AddTile(Decoded<tile_t>(event)), "");
    }
    if (event.channel != channels.frame) continue;
    ASSERT_EQ(assembler.AddManifest(Decoded<frame_t>(event)), TileAssembler::FrameResult::kComplete);
    ASSERT_LT(frame, rendered.images.size());
    EXPECT_EQ(assembler.image(), rendered.images[frame]) << "frame " << frame;
    ++frame;
  }
  EXPECT_EQ(frame, rendered.images.size());
  EXPECT_GT(rendered.images.front(), std::vector<uint8_t>()) << "frames have pixels";
  EXPECT_NE(rendered.images.front(), rendered.images.back()) << "the flag moves";
}

TEST(OfflineRender, WithoutALogOnlyDrawsFrames) {
  const Channels channels;
  int frames = 0;
  OfflineRender render(SmallScene(4), 1.0, channels, nullptr,
                       [&](int64_t, const render::Framebuffer&) { ++frames; });
  while (render.Advance()) {
  }
  EXPECT_EQ(frames, 4);
  EXPECT_EQ(render.stats().states, 0);
  EXPECT_EQ(render.stats().tiles, 0);
}

}  // namespace
}  // namespace flagsim
