#include "messages/checked_decode.hpp"

#include <gtest/gtest.h>

#include <random>

#include "tests/messages/message_fixtures.hpp"

namespace flagsim::wire {
namespace {

using testing::Encode;
constexpr size_t kLimit = 64 * 1024;

TEST(CheckedDecode, RoundTripsEveryCommand) {
  std::string error;
  const param_command_t param = testing::SomeParamCommand();
  const auto bytes = Encode(param);
  const auto decoded = CheckedDecode<param_command_t>(bytes.data(), bytes.size(), kLimit, &error);
  ASSERT_TRUE(decoded) << error;
  EXPECT_EQ(decoded->names, param.names);
  EXPECT_EQ(decoded->values, param.values);
  EXPECT_EQ(decoded->client_id, "test-client");

  const auto wind_bytes = Encode(testing::SomeWindCommand());
  const auto wind = CheckedDecode<wind_command_t>(wind_bytes.data(), wind_bytes.size(), kLimit, &error);
  ASSERT_TRUE(wind) << error;
  EXPECT_EQ(wind->velocity[0], 4);
  EXPECT_EQ(wind->ramp_time, 1.5);

  const auto key_bytes = Encode(testing::SomeKeyframeCommand());
  const auto keyframe = CheckedDecode<keyframe_command_t>(key_bytes.data(), key_bytes.size(), kLimit, &error);
  ASSERT_TRUE(keyframe) << error;
  EXPECT_EQ(keyframe->key.names, testing::SomeKey().names);
  EXPECT_EQ(keyframe->key.values, testing::SomeKey().values);
  EXPECT_EQ(keyframe->key.camera_fov, 40);

  const auto timeline_bytes = Encode(testing::SomeTimeline());
  const auto timeline =
      CheckedDecode<timeline_t>(timeline_bytes.data(), timeline_bytes.size(), kLimit, &error);
  ASSERT_TRUE(timeline) << error;
  ASSERT_EQ(timeline->keys.size(), 2u);
  EXPECT_EQ(timeline->keys[1].time, 4);
  EXPECT_TRUE(timeline->keys[0].has_camera);

  const auto state_bytes = Encode(testing::SomeState());
  const auto state = CheckedDecode<state_t>(state_bytes.data(), state_bytes.size(), kLimit, &error);
  ASSERT_TRUE(state) << error;
  EXPECT_EQ(state->position.size(), 18u);
  EXPECT_EQ(state->state_hash, -5);
}

TEST(CheckedDecode, RejectsTheWrongType) {
  std::string error;
  const auto bytes = Encode(testing::SomeWindCommand());
  EXPECT_FALSE(CheckedDecode<param_command_t>(bytes.data(), bytes.size(), kLimit, &error));
  EXPECT_NE(error.find("wrong type fingerprint"), std::string::npos);
}

TEST(CheckedDecode, RejectsOversizedMessages) {
  std::string error;
  const auto bytes = Encode(testing::SomeState());
  EXPECT_FALSE(CheckedDecode<state_t>(bytes.data(), bytes.size(), 16, &error));
  EXPECT_NE(error.find("limit"), std::string::npos);
}

TEST(CheckedDecode, SurvivesRandomBytes) {
  // Random garbage behind a correct fingerprint reaches the wire checker; none may crash it
  // or make decode allocate, and anything accepted must re-encode to the same bytes.
  std::mt19937 random(1);
  const auto valid = Encode(testing::SomeParamCommand());
  int accepted = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    std::vector<uint8_t> bytes(valid.begin(), valid.begin() + 8);
    const size_t size = 8 + random() % 96;
    while (bytes.size() < size) bytes.push_back(static_cast<uint8_t>(random()));
    if (trial % 2 == 0) {  // half: mutate a valid message instead, a few bytes
      bytes = valid;
      for (int k = 0; k < 3; ++k) bytes[8 + random() % (bytes.size() - 8)] = static_cast<uint8_t>(random());
    }
    std::string error;
    const auto decoded = CheckedDecode<param_command_t>(bytes.data(), bytes.size(), kLimit, &error);
    if (decoded) {
      ++accepted;
      EXPECT_EQ(Encode(*decoded), bytes);
    } else {
      EXPECT_FALSE(error.empty());
    }
  }
  EXPECT_GT(accepted, 0);  // mutations of strings' contents stay valid
}

}  // namespace
}  // namespace flagsim::wire
