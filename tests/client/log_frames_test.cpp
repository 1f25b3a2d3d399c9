#include "client/log_frames.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <set>
#include <string>
#include <vector>

#include "server/service/log_publisher.hpp"
#include "server/service/message_builders.hpp"
#include "server/service/tile_stream.hpp"

namespace flagsim {
namespace {

/// A 130 x 70 image (3 x 2 tiles of 64) whose every tile differs from one seed to the next.
render::Framebuffer Picture(int seed) {
  render::Framebuffer image;
  image.Resize(130, 70);
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      uint8_t* p = image.Pixel(x, y);
      p[0] = uint8_t(x + 3 * seed);
      p[1] = uint8_t(y * seed);
      p[2] = uint8_t(seed);
    }
  }
  return image;
}

/// Writes a log as a server's stream would give it to a recorder, losses and all.
class LogBuilder {
 public:
  LogBuilder()
      : path_(std::string(::testing::TempDir()) + "/" + std::to_string(getpid()) + "_frames.lcmlog") {
    log_ = std::make_unique<LogPublisher>(path_, 1700000000000000);
  }
  ~LogBuilder() { std::remove(path_.c_str()); }

  void Params(double frame_rate) {
    Scene scene;
    scene.service.frame_rate = frame_rate;
    log_->Publish(channels_.params, MakeParamsMessage(scene, log_->utime()));
  }
  /// Frame of Picture(seed) at `sim_time`; tiles in `lost` (by index in the frame) are not
  /// logged; `logged` false: the whole frame happened before the recorder started.
  void Frame(int seed, double sim_time, const std::set<size_t>& lost = {}, bool logged = true) {
    log_->AdvanceTo(sim_time);
    FrameInfo info;
    info.sim_time = sim_time;
    const EncodedFrame frame = stream_.Encode(Picture(seed), info, 1);
    if (!logged) return;
    for (size_t i = 0; i < frame.tiles.size(); ++i) {
      if (lost.count(i) == 0) log_->Publish(channels_.tile, frame.tiles[i]);
    }
    log_->Publish(channels_.frame, frame.manifest);
  }
  void RequestKeyframe() { stream_.RequestKeyframe(1); }
  /// Closes the log; its path.
  const std::string& Close() {
    log_->Close();
    log_.reset();
    return path_;
  }
  const Channels& channels() const { return channels_; }

 private:
  std::string path_;
  Channels channels_;
  std::unique_ptr<LogPublisher> log_;
  TileStream stream_{64};
};

/// The seed of the picture `image` is, or -1.
int SeedOf(const std::vector<uint8_t>& image, int max_seed = 40) {
  for (int seed = 0; seed <= max_seed; ++seed) {
    if (image == Picture(seed).rgb) return seed;
  }
  return -1;
}

/// The images LogFrames gives, as the seeds of the pictures they are.
std::vector<int> Seeds(LogFrames* frames) {
  std::vector<int> seeds;
  while (frames->Next()) seeds.push_back(SeedOf(frames->image()));
  return seeds;
}

TEST(LogFrames, AWholeLogGivesEveryFrameInOrder) {
  LogBuilder builder;
  builder.Params(10);
  for (int k = 0; k < 10; ++k) builder.Frame(k, k * 0.1);
  const std::string& path = builder.Close();
  const LogSurvey survey = SurveyLog(path, builder.channels());
  EXPECT_EQ(survey.manifests, 10);
  EXPECT_EQ(survey.keyframes, 1);
  EXPECT_EQ(survey.width, 130);
  EXPECT_EQ(survey.frame_rate, 10);
  EXPECT_EQ(survey.frame_rate_source, "PARAMS");
  LogFrames frames(path, builder.channels(), survey.frame_rate);
  EXPECT_EQ(Seeds(&frames), (std::vector<int>{0, 1, 2, 3, 4, 5, 6, 7, 8, 9}));
  EXPECT_EQ(frames.report().lost + frames.report().gaps + frames.report().dropped, 0);
  EXPECT_EQ(frames.reader().end(), EventLogReader::End::kClean);
}

// A recorder that joins a still picture mid-stream gets no keyframe: 2 of its 6 tiles a frame
// from the rolling refresh, so the third frame is the first whole one, and the export starts there.
TEST(LogFrames, ALogRecordedMidStreamStartsAtItsFirstWholeFrame) {
  LogBuilder builder;
  for (int k = 0; k < 3; ++k) builder.Frame(0, k * 0.1, {}, false);  // before the recorder
  for (int k = 3; k < 9; ++k) builder.Frame(0, k * 0.1);
  const std::string& path = builder.Close();
  const LogSurvey survey = SurveyLog(path, builder.channels());
  EXPECT_EQ(survey.keyframes, 0);
  EXPECT_EQ(survey.width, 130);
  LogFrames frames(path, builder.channels(), 10);
  EXPECT_EQ(Seeds(&frames), (std::vector<int>{0, 0, 0, 0}));
  EXPECT_EQ(frames.report().skipped_before_whole, 2);
}

TEST(LogFrames, AFrameWithTilesLostRepeatsTheLastWholeOne) {
  LogBuilder builder;
  for (int k = 0; k < 6; ++k) builder.Frame(k, k * 0.1, k == 3 ? std::set<size_t>{4} : std::set<size_t>{});
  const std::string& path = builder.Close();
  LogFrames frames(path, builder.channels(), 10);
  std::vector<bool> repeated;
  std::vector<int> seeds;
  while (frames.Next()) {
    repeated.push_back(frames.repeated());
    seeds.push_back(SeedOf(frames.image()));
  }
  EXPECT_EQ(seeds, (std::vector<int>{0, 1, 2, 2, 4, 5}));
  EXPECT_EQ(repeated, (std::vector<bool>{false, false, false, true, false, false}));
  EXPECT_EQ(frames.report().lost, 1);
}

TEST(LogFrames, FrameTimesMissedRepeatTheLastFrame) {
  LogBuilder builder;
  for (const double time : {0.0, 0.1, 0.2, 0.5, 0.6}) builder.Frame(int(std::lround(time * 10)), time);
  const std::string& path = builder.Close();
  LogFrames frames(path, builder.channels(), 10);
  EXPECT_EQ(Seeds(&frames), (std::vector<int>{0, 1, 2, 2, 2, 5, 6}));
  EXPECT_EQ(frames.report().gaps, 2);
  LogFrames untimed(path, builder.channels(), 0);  // no frame rate: one image per frame
  EXPECT_EQ(Seeds(&untimed), (std::vector<int>{0, 1, 2, 5, 6}));
}

TEST(LogFrames, AFrameBetweenTwoFrameTimesIsDropped) {
  LogBuilder builder;
  builder.Frame(0, 0.0);
  builder.Frame(1, 0.1);
  builder.Frame(2, 0.13);  // a keyframe a REFRESH asked for, say
  builder.Frame(3, 0.2);
  const std::string& path = builder.Close();
  LogFrames frames(path, builder.channels(), 10);
  EXPECT_EQ(Seeds(&frames), (std::vector<int>{0, 1, 3}));
  EXPECT_EQ(frames.report().dropped, 1);
}

TEST(LogFrames, ANewSessionInTheLogCountsAfresh) {
  LogBuilder builder;
  builder.Frame(0, 5.0);
  builder.Frame(1, 5.1);
  builder.Frame(2, 0.0);  // time went back: another session
  builder.Frame(3, 0.1);
  const std::string& path = builder.Close();
  LogFrames frames(path, builder.channels(), 10);
  EXPECT_EQ(Seeds(&frames), (std::vector<int>{0, 1, 2, 3}));
  EXPECT_EQ(frames.report().time_jumps, 1);
}

TEST(LogFrames, ACutLogGivesTheFramesBeforeTheCut) {
  LogBuilder builder;
  for (int k = 0; k < 6; ++k) builder.Frame(k, k * 0.1);
  const std::string& path = builder.Close();
  std::ifstream in(path, std::ios::binary);
  std::vector<char> bytes((std::istreambuf_iterator<char>(in)), {});
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(bytes.data(), std::streamsize(bytes.size() - 100));
  LogFrames frames(path, builder.channels(), 10);
  EXPECT_EQ(Seeds(&frames), (std::vector<int>{0, 1, 2, 3, 4}));
  EXPECT_EQ(frames.reader().end(), EventLogReader::End::kTruncated);
}

TEST(LogFrames, WithoutParamsTheRateComesFromTheFrameTimes) {
  LogBuilder builder;
  for (int k = 0; k < 8; ++k) builder.Frame(k, k * 0.04);
  const LogSurvey survey = SurveyLog(builder.Close(), builder.channels());
  EXPECT_NEAR(survey.frame_rate, 25, 1e-9);
  EXPECT_EQ(survey.frame_rate_source, "FRAME times");
}

// A damaged log may claim any rate: one no server draws is not believed (keeping the timing at
// 1e12 Hz would repeat a frame for every picosecond between two frames).
TEST(LogFrames, ARateNoServerDrawsIsNotBelieved) {
  LogBuilder claims;
  claims.Params(1e12);
  for (int k = 0; k < 8; ++k) claims.Frame(k, k * 0.04);
  const LogSurvey survey = SurveyLog(claims.Close(), claims.channels());
  EXPECT_NEAR(survey.frame_rate, 25, 1e-9);
  EXPECT_EQ(survey.frame_rate_source, "FRAME times");

  LogBuilder crowded;
  for (int k = 0; k < 8; ++k) crowded.Frame(k, k * 1e-6);
  EXPECT_EQ(SurveyLog(crowded.Close(), crowded.channels()).frame_rate, 0);
}

// Frames fall on step boundaries: at 30 Hz with 2 ms steps, intervals of 16 and 17 steps.
TEST(EstimateFrameRate, TheMeanOfTheUsualIntervals) {
  std::vector<double> times;
  for (int k = 0; k < 90; ++k) times.push_back(0.002 * std::ceil(k / 30.0 / 0.002));
  EXPECT_NEAR(EstimateFrameRate(times), 30, 30 * 0.002);
  times.erase(times.begin() + 40, times.begin() + 45);  // frames skipped
  times.insert(times.begin() + 20, times[19] + 0.004);  // an extra frame
  EXPECT_NEAR(EstimateFrameRate(times), 30, 30 * 0.002);
  EXPECT_EQ(EstimateFrameRate({1.0}), 0);
  EXPECT_EQ(EstimateFrameRate({}), 0);
}

}  // namespace
}  // namespace flagsim
