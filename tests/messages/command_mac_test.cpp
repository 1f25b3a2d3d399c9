// The MAC of a command: HMAC-SHA-256 of channel, separator and encoding, which every field of
// the command and the channel change, and which a signer's stamp carries.
#include "messages/command_mac.hpp"

#include <gtest/gtest.h>

#include "tests/messages/message_fixtures.hpp"

namespace flagsim {
namespace {

CommandKey TestKey(uint8_t first = 0) {
  CommandKey key;
  key.name = "ops";
  for (size_t k = 0; k < key.secret.size(); ++k) key.secret[k] = static_cast<uint8_t>(first + k);
  return key;
}

std::string Hex(const Mac& mac) {
  std::string text;
  char digits[3];
  for (const uint8_t byte : mac) {
    std::snprintf(digits, sizeof(digits), "%02x", byte);
    text += digits;
  }
  return text;
}

// The expected value is another implementation's: with the key 00 01 .. 1f,
//   printf 'FLAG_WIND\0abc' | openssl dgst -sha256 -mac HMAC -macopt hexkey:000102...1f
TEST(CommandMac, IsHmacSha256OfChannelSeparatorAndEncoding) {
  const uint8_t encoded[] = {'a', 'b', 'c'};
  EXPECT_EQ(Hex(ComputeMac(TestKey(), "FLAG_WIND", encoded, sizeof(encoded))),
            "8eb3df71b0d5e821840329a3d2b2ac5bb3227f58671ca71e1a828990600d8416");
}

TEST(CommandMac, EveryFieldTheChannelAndTheKeyChangeIt) {
  const CommandKey key = TestKey();
  wind_command_t command = testing::SomeWindCommand();
  command.key_id = "ops";
  const Mac mac = MacOf(key, "FLAG_WIND", command);
  EXPECT_EQ(MacOf(key, "FLAG_WIND", command), mac);
  EXPECT_NE(MacOf(TestKey(1), "FLAG_WIND", command), mac);
  EXPECT_NE(MacOf(key, "OTHER_WIND", command), mac);
  const auto changed = [&](auto change) {
    wind_command_t copy = command;
    change(copy);
    return MacOf(key, "FLAG_WIND", copy) != mac;
  };
  EXPECT_TRUE(changed([](wind_command_t& c) { c.utime += 1; }));
  EXPECT_TRUE(changed([](wind_command_t& c) { c.sequence += 1; }));
  EXPECT_TRUE(changed([](wind_command_t& c) { c.client_id += "x"; }));
  EXPECT_TRUE(changed([](wind_command_t& c) { c.key_id = "lab"; }));
  EXPECT_TRUE(changed([](wind_command_t& c) { c.velocity[2] = -c.velocity[2]; }));
  EXPECT_TRUE(changed([](wind_command_t& c) { c.ramp_time += 1e-9; }));
  EXPECT_FALSE(changed([](wind_command_t& c) { c.mac[5] ^= 1; }));  // the carried MAC is not signed
}

TEST(CommandMac, TheSameBytesUnderAnotherTypeDiffer) {
  // A REFRESH and a WIND with the same header: the encoding starts with each type's fingerprint.
  const CommandKey key = TestKey();
  refresh_request_t refresh{};
  wind_command_t wind{};
  refresh.client_id = wind.client_id = "c";
  EXPECT_NE(MacOf(key, "FLAG_X", refresh), MacOf(key, "FLAG_X", wind));
}

TEST(CommandSigner, StampsTimeKeyAndAMacThatChecksOut) {
  wind_command_t command = testing::SomeWindCommand();
  CommandSigner(TestKey()).Stamp("FLAG_WIND", command);
  EXPECT_EQ(command.key_id, "ops");
  EXPECT_GT(command.utime, 1'700'000'000'000'000);
  EXPECT_TRUE(MacMatches(MacOf(TestKey(), "FLAG_WIND", command), command.mac));
  EXPECT_FALSE(MacMatches(MacOf(TestKey(), "FLAG_PARAM", command), command.mac));
}

TEST(CommandSigner, WithoutAKeyOnlyDates) {
  wind_command_t command = testing::SomeWindCommand();
  CommandSigner().Stamp("FLAG_WIND", command);
  EXPECT_EQ(command.key_id, "");
  for (const uint8_t byte : command.mac) EXPECT_EQ(byte, 0);
}

}  // namespace
}  // namespace flagsim
