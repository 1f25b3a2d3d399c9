// The recorder on an in-process bus (memq://): it records the server's channels and no others,
// asks for a keyframe at its start and again each second while no checkpoint has come (a few
// times at most), and a full disk ends its log with the writer's message.
#include "client/log_recorder.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <string>
#include <vector>

#include "messages/event_log_reader.hpp"

namespace flagsim {
namespace {

std::string TempPath(const std::string& name) {
  return std::string(::testing::TempDir()) + "/" + std::to_string(getpid()) + "_" + name;
}

class LogRecorderTest : public ::testing::Test {
 protected:
  LogRecorderTest() : bus_("memq://") {}
  ~LogRecorderTest() override { std::remove(path_.c_str()); }

  void Deliver(const std::string& channel) {
    const std::vector<uint8_t> bytes(100, 7);
    bus_.Publish(channel, bytes.data(), bytes.size());
    bus_.HandleAll();
  }

  Bus bus_;
  Channels channels_;
  std::string path_ = TempPath("recorder.lcmlog");
};

TEST_F(LogRecorderTest, RecordsTheServersChannelsAndNoOthers) {
  {
    LogRecorder recorder(bus_, channels_, path_);
    Deliver(channels_.state);
    Deliver(channels_.tile);
    Deliver("OTHER_STATE");
    EXPECT_EQ(recorder.events(), 2);
  }
  EventLogReader log(path_);
  LogEvent event;
  std::vector<std::string> recorded;
  while (log.Next(&event)) recorded.push_back(event.channel);
  EXPECT_EQ(recorded, (std::vector<std::string>{channels_.state, channels_.tile}));
  EXPECT_EQ(log.end(), EventLogReader::End::kClean);
}

// Simulated seconds on the caller's clock.
TEST_F(LogRecorderTest, AsksForAKeyframeAtOnceAndAgainEachSecondUntilACheckpointComes) {
  LogRecorder recorder(bus_, channels_, path_);
  EXPECT_TRUE(recorder.KeyframeRequestDue(10.0));
  EXPECT_FALSE(recorder.KeyframeRequestDue(10.5));
  EXPECT_TRUE(recorder.KeyframeRequestDue(11.0)) << "no checkpoint a second later: asked again";
  Deliver(channels_.checkpoint);
  EXPECT_EQ(recorder.checkpoints(), 1);
  EXPECT_FALSE(recorder.KeyframeRequestDue(12.0)) << "the log has its checkpoint";
  EXPECT_FALSE(recorder.KeyframeRequestDue(20.0));
}

TEST_F(LogRecorderTest, GivesUpAskingWhenNobodyAnswers) {
  LogRecorder recorder(bus_, channels_, path_);
  int asked = 0;
  for (double now = 0; now < 30; now += 0.25) asked += recorder.KeyframeRequestDue(now);
  EXPECT_EQ(asked, LogRecorder::kAsks);
}

TEST_F(LogRecorderTest, AFullDiskEndsTheLogWithTheWritersMessage) {
  LogRecorder recorder(bus_, channels_, "/dev/full");
  Deliver(channels_.state);
  EXPECT_TRUE(recorder.failed());
  EXPECT_EQ(recorder.events(), 0);
  EXPECT_NE(recorder.error().find("the disk is full"), std::string::npos) << recorder.error();
  Deliver(channels_.checkpoint);
  EXPECT_EQ(recorder.checkpoints(), 0) << "nothing is written after the failure";
}

}  // namespace
}  // namespace flagsim
