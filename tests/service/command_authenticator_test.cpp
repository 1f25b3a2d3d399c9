// Who may steer the server: each refusal (unsigned, unknown key, bad MAC, stale, replayed) with
// its reason, retries that pass, and refused commands that leave nothing behind.
#include "server/service/command_authenticator.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "flagsim/wind_command_t.hpp"

namespace flagsim {
namespace {

using Refusal = CommandAuthenticator::Refusal;

constexpr int64_t kNow = 1'800'000'000'000'000;  // µs since the Unix epoch: the server's clock
const std::string kChannel = "FLAG_WIND";

CommandKey Key(const std::string& name, uint8_t fill) {
  CommandKey key;
  key.name = name;
  key.secret.fill(fill);
  return key;
}

/// A wind command from `client`, signed with `key` at `utime`.
wind_command_t Signed(const CommandKey& key, int64_t sequence, int64_t utime,
                      const std::string& client = "c1") {
  wind_command_t command{};
  command.client_id = client;
  command.sequence = sequence;
  command.utime = utime;
  command.velocity[0] = 5;
  command.key_id = key.name;
  const Mac mac = MacOf(key, kChannel, command);
  std::copy(mac.begin(), mac.end(), command.mac);
  return command;
}

class CommandAuthenticatorTest : public ::testing::Test {
 protected:
  CommandAuthenticator::Verdict Check(const wind_command_t& command, int64_t now = kNow) {
    return authenticator_.Check(kChannel, command, now);
  }
  /// The refusal's kind, and that its reason starts with the kind's name ("" when it passes).
  Refusal RefusalOf(const wind_command_t& command, int64_t now = kNow) {
    const CommandAuthenticator::Verdict verdict = Check(command, now);
    if (verdict.refusal == Refusal::kNone)
      EXPECT_EQ(verdict.reason, "");
    else
      EXPECT_EQ(verdict.reason.rfind(RefusalName(verdict.refusal), 0), 0u) << verdict.reason;
    return verdict.refusal;
  }

  const CommandKey ops_ = Key("ops", 1), lab_ = Key("lab", 2);
  CommandAuthenticator authenticator_{{ops_, lab_}};
};

TEST(CommandAuthenticatorWithoutKeys, PassesEverythingAndSaysSo) {
  CommandAuthenticator open;
  EXPECT_FALSE(open.enabled());
  EXPECT_EQ(open.Describe(), "none: commands are unauthenticated");
  wind_command_t command{};
  EXPECT_EQ(open.Check(kChannel, command, kNow).refusal, Refusal::kNone);
  EXPECT_EQ(open.Check(kChannel, command, kNow).refusal, Refusal::kNone);  // no replay check either
}

TEST_F(CommandAuthenticatorTest, DescribesItsKeysButNotTheirSecrets) {
  EXPECT_EQ(authenticator_.Describe(), "HMAC-SHA-256, keys ops, lab");
}

TEST_F(CommandAuthenticatorTest, ASignedFreshCommandPassesUnderEitherKey) {
  EXPECT_EQ(RefusalOf(Signed(ops_, 1, kNow)), Refusal::kNone);
  EXPECT_EQ(RefusalOf(Signed(lab_, 1, kNow - 29'000'000)), Refusal::kNone);
}

TEST_F(CommandAuthenticatorTest, UnsignedAndUnknownKeysAreRefused) {
  wind_command_t command = Signed(ops_, 1, kNow);
  command.key_id = "";
  EXPECT_EQ(RefusalOf(command), Refusal::kUnsigned);
  EXPECT_EQ(RefusalOf(Signed(Key("stranger", 1), 1, kNow)), Refusal::kUnknownKey);
}

// The name of a key the server does not have is quoted as printable text, cut to the 32
// characters a key's name may have.
TEST_F(CommandAuthenticatorTest, AnUnknownKeysNameIsQuotedPrintableAndCut) {
  const std::string reason =
      Check(Signed(Key("\x1b]0;owned\x07" + std::string(5000, 'k'), 1), 1, kNow)).reason;
  EXPECT_EQ(reason,
            "unknown key: '\\x1b]0;owned\\x07" + std::string(16, 'k') + "...' is none of this server's keys");
}

TEST_F(CommandAuthenticatorTest, AForgedOrAlteredCommandHasABadMac) {
  // Claims the key "ops" but was signed with another secret.
  EXPECT_EQ(RefusalOf(Signed(Key("ops", 9), 1, kNow)), Refusal::kBadMac);
  wind_command_t altered = Signed(ops_, 2, kNow);
  altered.velocity[0] = 50;
  EXPECT_EQ(RefusalOf(altered), Refusal::kBadMac);
  // Signed for another channel.
  EXPECT_EQ(authenticator_.Check("FLAG_PARAM", Signed(ops_, 3, kNow), kNow).refusal, Refusal::kBadMac);
  EXPECT_EQ(RefusalOf(Signed(ops_, 4, kNow)), Refusal::kNone);  // the client goes on
}

TEST_F(CommandAuthenticatorTest, ACommandFromOutsideTheWindowIsStaleEitherWay) {
  EXPECT_EQ(RefusalOf(Signed(ops_, 1, kNow - 31'000'000)), Refusal::kStale);
  EXPECT_EQ(RefusalOf(Signed(ops_, 2, kNow + 31'000'000)), Refusal::kStale);
  EXPECT_NE(Check(Signed(ops_, 3, kNow - 45'000'000)).reason.find("45.0 s behind"), std::string::npos);
  EXPECT_EQ(RefusalOf(Signed(ops_, 4, std::numeric_limits<int64_t>::min())), Refusal::kStale);
  EXPECT_EQ(RefusalOf(Signed(ops_, 5, std::numeric_limits<int64_t>::max())), Refusal::kStale);
}

TEST_F(CommandAuthenticatorTest, ARetryPassesButTheSameBytesAgainAreReplayed) {
  const wind_command_t first = Signed(ops_, 1, kNow);
  EXPECT_EQ(RefusalOf(first), Refusal::kNone);
  EXPECT_EQ(RefusalOf(first, kNow + 100), Refusal::kReplayed);
  const wind_command_t retry = Signed(ops_, 1, kNow + 500'000);  // resent 0.5 s later, dated anew
  EXPECT_EQ(RefusalOf(retry, kNow + 500'000), Refusal::kNone);
  EXPECT_EQ(RefusalOf(retry, kNow + 600'000), Refusal::kReplayed);
  EXPECT_EQ(RefusalOf(first, kNow + 600'000), Refusal::kReplayed);
}

TEST_F(CommandAuthenticatorTest, AnOlderSequenceIsReplayedPerClientAndKey) {
  EXPECT_EQ(RefusalOf(Signed(ops_, 5, kNow)), Refusal::kNone);
  EXPECT_EQ(RefusalOf(Signed(ops_, 4, kNow + 1)), Refusal::kReplayed);
  EXPECT_EQ(RefusalOf(Signed(ops_, 4, kNow + 1, "c2")), Refusal::kNone);  // another client
  EXPECT_EQ(RefusalOf(Signed(lab_, 4, kNow + 1)), Refusal::kNone);        // another key
  EXPECT_EQ(RefusalOf(Signed(ops_, 6, kNow + 2)), Refusal::kNone);
}

TEST_F(CommandAuthenticatorTest, RefusedCommandsLeaveNothingBehind) {
  // A forged command with a high sequence must not lock its client out.
  EXPECT_EQ(RefusalOf(Signed(Key("ops", 9), 1000, kNow)), Refusal::kBadMac);
  EXPECT_EQ(RefusalOf(Signed(ops_, 1000, kNow - 40'000'000)), Refusal::kStale);
  EXPECT_EQ(RefusalOf(Signed(ops_, 1, kNow)), Refusal::kNone);
}

TEST_F(CommandAuthenticatorTest, ManyClientsLaterStillCatchesAFreshReplay) {
  const wind_command_t watched = Signed(ops_, 1, kNow);
  EXPECT_EQ(RefusalOf(watched), Refusal::kNone);
  // Thousands of old clients come and go; the memory forgets the stale ones, not the fresh one.
  for (int k = 0; k < 5000; ++k)
    EXPECT_EQ(Check(Signed(ops_, 1, kNow - 29'000'000, "old" + std::to_string(k)), kNow).refusal,
              Refusal::kNone);
  for (int k = 0; k < 5000; ++k)
    ASSERT_EQ(Check(Signed(ops_, 1, kNow + 2'000'000, "new" + std::to_string(k)), kNow + 2'000'000).refusal,
              Refusal::kNone);
  EXPECT_EQ(RefusalOf(watched, kNow + 2'000'000), Refusal::kReplayed);
}

}  // namespace
}  // namespace flagsim
