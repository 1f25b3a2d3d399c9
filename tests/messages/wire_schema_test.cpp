#include "messages/wire_schema.hpp"

#include <gtest/gtest.h>

#include <algorithm>

#include "tests/messages/message_fixtures.hpp"

namespace flagsim::wire {
namespace {

using testing::Encode;

TEST(WireSchema, KnowsEveryTypeAndItsFields) {
  const Schema& schema = Schema::Flagsim();
  for (const char* type : {"ack_t", "camera_command_t", "frame_t", "keyframe_command_t", "param_command_t",
                           "parameter_t", "params_t", "refresh_request_t", "state_t", "status_t", "tile_t",
                           "timeline_key_t", "timeline_t", "wind_command_t"}) {
    EXPECT_NE(schema.Find(type), nullptr) << type;
  }
  const StructLayout* state = schema.Find("state_t");
  ASSERT_NE(state, nullptr);
  EXPECT_EQ(state->fields.front().name, "utime");
  EXPECT_EQ(state->fields.back().name, "position");
  EXPECT_EQ(state->fields.back().dimensions.front().count_field, "num_values");
  const auto names = [](const StructLayout& layout) {
    std::vector<std::string> list;
    for (const Field& field : layout.fields) list.push_back(field.name);
    return list;
  };
  const std::vector<std::string> state_fields = names(*state);
  const auto wind = std::find(state_fields.begin(), state_fields.end(), "wind");
  ASSERT_GE(std::distance(wind, state_fields.end()), 3);
  EXPECT_EQ(*(wind + 1), "wind_gust");
  EXPECT_EQ(*(wind + 2), "kinetic_energy");
  const StructLayout* frame = schema.Find("frame_t");
  ASSERT_NE(frame, nullptr);
  const std::vector<std::string> frame_fields = names(*frame);
  ASSERT_GE(frame_fields.size(), 4u);
  EXPECT_EQ(std::vector<std::string>(frame_fields.end() - 4, frame_fields.end()),
            (std::vector<std::string>{"projection", "camera_eye", "camera_target", "camera_fov"}));
  EXPECT_EQ(frame->fields[frame->fields.size() - 3].dimensions.front().fixed_size, 3);
}

TEST(WireSchema, ParsesCommentsConstantsNestingAndFixedArrays) {
  const std::vector<std::pair<std::string_view, std::string_view>> sources = {{"t", R"(package p; /* block
    comment */ struct inner_t { int16_t a; }
    struct outer_t {
      // line comment
      const int8_t A = 1, B = -2;
      const double X = 1.5e3;
      int32_t n;
      p.inner_t items[n][2];
      double v[3];
      string s;
    })"}};
  const Schema schema(sources);
  const StructLayout* outer = schema.Find("outer_t");
  ASSERT_NE(outer, nullptr);
  ASSERT_EQ(outer->fields.size(), 4u);
  EXPECT_EQ(outer->fields[1].type, Primitive::kStruct);
  EXPECT_EQ(outer->fields[1].struct_name, "inner_t");
  EXPECT_EQ(outer->fields[1].dimensions[1].fixed_size, 2);
  EXPECT_EQ(outer->fields[2].dimensions[0].fixed_size, 3);
}

TEST(WireSchema, AcceptsWhatLcmGenEncodes) {
  const Schema& schema = Schema::Flagsim();
  const auto accepts = [&](const char* type, const std::vector<uint8_t>& bytes) {
    EXPECT_EQ(schema.CheckWire(type, bytes.data(), bytes.size()), "") << type;
  };
  accepts("param_command_t", Encode(testing::SomeParamCommand()));
  accepts("wind_command_t", Encode(testing::SomeWindCommand()));
  accepts("state_t", Encode(testing::SomeState()));
  accepts("params_t", Encode(testing::SomeParams()));
  accepts("keyframe_command_t", Encode(testing::SomeKeyframeCommand()));
  accepts("timeline_t", Encode(testing::SomeTimeline()));
  accepts("tile_t", Encode(testing::SomeTile()));
  accepts("frame_t", Encode(testing::SomeFrame()));
  accepts("ack_t", Encode(ack_t{}));
  accepts("status_t", Encode(status_t{}));
  accepts("camera_command_t", Encode(camera_command_t{}));
  accepts("refresh_request_t", Encode(refresh_request_t{}));
}

TEST(WireSchema, RejectsEveryTruncation) {
  const std::vector<std::pair<const char*, std::vector<uint8_t>>> messages = {
      {"params_t", Encode(testing::SomeParams())},
      {"keyframe_command_t", Encode(testing::SomeKeyframeCommand())},  // with a nested key
      {"timeline_t", Encode(testing::SomeTimeline())}};
  for (const auto& [type, bytes] : messages) {
    for (size_t size = 0; size < bytes.size(); ++size) {
      EXPECT_NE(Schema::Flagsim().CheckWire(type, bytes.data(), size), "") << type << " " << size;
    }
  }
}

TEST(WireSchema, RejectsTrailingBytes) {
  std::vector<uint8_t> bytes = Encode(testing::SomeWindCommand());
  bytes.push_back(0);
  EXPECT_NE(Schema::Flagsim().CheckWire("wind_command_t", bytes.data(), bytes.size()).find("left over"),
            std::string::npos);
}

/// Offset of param_command_t's num_assignments in SomeParamCommand's encoding.
size_t CountOffset() {
  // fingerprint 8, utime 8, client_id 4 + 12, sequence 8, key_id "" 4 + 1, mac 32, reset_to_scene 1
  return 8 + 8 + 4 + std::string("test-client").size() + 1 + 8 + 5 + 32 + 1;
}

TEST(WireSchema, RejectsHugeAndNegativeCounts) {
  std::vector<uint8_t> bytes = Encode(testing::SomeParamCommand());
  const size_t at = CountOffset();
  ASSERT_EQ(bytes[at + 3], 2);  // num_assignments, big-endian
  for (const uint32_t count : {0x7fffffffu, 0xffffffffu, 0x80000000u, 1000u}) {
    for (int i = 0; i < 4; ++i) bytes[at + i] = static_cast<uint8_t>(count >> (24 - 8 * i));
    const std::string error = Schema::Flagsim().CheckWire("param_command_t", bytes.data(), bytes.size());
    EXPECT_NE(error.find("names:"), std::string::npos) << count << ": " << error;
  }
}

TEST(WireSchema, RejectsBadStringLengths) {
  std::vector<uint8_t> bytes = Encode(testing::SomeParamCommand());
  const size_t at = 8 + 8;  // client_id's length
  for (const uint32_t length : {0u, 0xffffffffu, 0x7fffffffu, 13u}) {
    for (int i = 0; i < 4; ++i) bytes[at + i] = static_cast<uint8_t>(length >> (24 - 8 * i));
    EXPECT_NE(Schema::Flagsim().CheckWire("param_command_t", bytes.data(), bytes.size()), "") << length;
  }
}

}  // namespace
}  // namespace flagsim::wire
