// The protocol's binary frames: the server's laid out as the spec says, the client's parsed
// with every length checked, whatever bytes arrive.
#include "client/gateway/foxglove_wire.hpp"

#include <gtest/gtest.h>

#include <random>

namespace flagsim::gateway {
namespace {

std::string Bytes(std::initializer_list<int> values) {
  std::string bytes;
  for (int value : values) bytes.push_back(static_cast<char>(value));
  return bytes;
}

TEST(FoxgloveWire, MessageDataHeadIsOpcodeSubscriptionAndTimestampLittleEndian) {
  EXPECT_EQ(MessageDataHead(0x04030201, 0x0c0b0a0908070605ull),
            Bytes({1, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12}));
}

TEST(FoxgloveWire, ServiceCallResponseCarriesItsEncoding) {
  EXPECT_EQ(ServiceCallResponse(7, 9, "json", "{}"),
            Bytes({3, 7, 0, 0, 0, 9, 0, 0, 0, 4, 0, 0, 0, 'j', 's', 'o', 'n', '{', '}'}));
}

TEST(FoxgloveWire, ClientFramesParse) {
  std::string error;
  const std::string data_frame = Bytes({1, 5, 0, 0, 0, 'x', 'y'});  // the parse points into it
  const auto data = ParseClientBinary(data_frame, &error);
  ASSERT_TRUE(data) << error;
  EXPECT_EQ(data->opcode, kClientMessageData);
  EXPECT_EQ(data->channel, 5u);
  EXPECT_EQ(data->payload, "xy");
  const std::string call_frame = Bytes({2, 1, 0, 0, 0, 2, 1, 0, 0, 4, 0, 0, 0, 'j', 's', 'o', 'n', '{', '}'});
  const auto call = ParseClientBinary(call_frame, &error);
  ASSERT_TRUE(call) << error;
  EXPECT_EQ(call->service, 1u);
  EXPECT_EQ(call->call, 258u);
  EXPECT_EQ(call->encoding, "json");
  EXPECT_EQ(call->payload, "{}");
}

TEST(FoxgloveWire, ShortLyingOrUnknownFramesAreRefusedWithAReason) {
  std::string error;
  EXPECT_FALSE(ParseClientBinary("", &error));
  EXPECT_FALSE(ParseClientBinary(Bytes({1, 5, 0}), &error));
  EXPECT_NE(error.find("at least 5"), std::string::npos) << error;
  EXPECT_FALSE(ParseClientBinary(Bytes({2, 1, 0, 0, 0, 2, 0, 0, 0, 9, 0, 0, 0, 'j'}), &error));
  EXPECT_NE(error.find("claims 9 bytes; 1 follow"), std::string::npos) << error;
  EXPECT_FALSE(ParseClientBinary(Bytes({2, 1, 0, 0, 0, 2, 0, 0, 0, 255, 255, 255, 255}), &error));
  EXPECT_FALSE(ParseClientBinary(Bytes({9, 0, 0, 0, 0}), &error));
  EXPECT_NE(error.find("opcode 9"), std::string::npos) << error;
}

TEST(FoxgloveWire, RandomBytesNeverReadOutsideTheFrame) {
  std::mt19937 random(12);
  for (int trial = 0; trial < 20000; ++trial) {
    std::string frame(random() % 40, '\0');
    for (char& c : frame) c = static_cast<char>(random());
    if (!frame.empty() && trial % 2 == 0) frame[0] = static_cast<char>(1 + trial % 3);
    std::string error;
    const auto parsed = ParseClientBinary(frame, &error);
    if (parsed) {
      EXPECT_GE(parsed->payload.data(), frame.data());
      EXPECT_LE(parsed->payload.data() + parsed->payload.size(), frame.data() + frame.size());
    } else {
      EXPECT_FALSE(error.empty());
    }
  }
}

}  // namespace
}  // namespace flagsim::gateway
