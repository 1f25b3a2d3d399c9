// The server's command side with keys (flagd --key-file), on an in-process bus (memq://): what
// is signed is taken and journaled with its sender; unsigned, unknown-key, forged, stale and
// replayed commands are refused with their reason and change nothing; a flood of forgeries is
// counted; a reader's question needs no signature.
#include <gtest/gtest.h>

#include "client/command_client.hpp"
#include "client/stream_reader.hpp"
#include "flagsim/applied_command_t.hpp"
#include "server/service/command_intake.hpp"
#include "server/service/server.hpp"
#include "tests/messages/message_fixtures.hpp"
#include "tests/service/simulated_clock.hpp"

namespace flagsim {
namespace {

// With keys, only commands signed with one of them steer the server; the rest are answered with
// the kind of refusal, counted, and change nothing.
class SignedCommandIntakeTest : public ::testing::Test {
 protected:
  static CommandKey Key(const std::string& name, uint8_t fill) {
    CommandKey key;
    key.name = name;
    key.secret.fill(fill);
    return key;
  }
  ServerOptions WithKeys() const {
    ServerOptions options = clock_.ServerOnIt();
    options.command_keys = {Key("ops", 7)};
    return options;
  }

  SignedCommandIntakeTest() : bus_("memq://"), server_(bus_, channels_, Scene{}, WithKeys()) {
    bus_.Subscribe(channels_.wind, [this](const std::string&, const uint8_t* data, size_t size) {
      sent_.assign(data, data + size);  // the bytes a client put on the bus: what a recorder sees
    });
    SubscribeDecoded<ack_t>(
        bus_, channels_.ack, [this](const ack_t& ack) { acks_.push_back(ack); }, nullptr, 100000);
    SubscribeDecoded<applied_command_t>(
        bus_, channels_.applied, [this](const applied_command_t& applied) { applied_.push_back(applied); });
  }

  /// A wind command sent by a client that signs with `signer`, waited for.
  CommandOutcome SendWind(CommandSigner signer, double speed) {
    CommandClient client(bus_, channels_, 5.0, std::move(signer), clock_.Reader());
    client.WhileWaiting([this] { clock_.Step(server_); });
    wind_command_t command{};
    command.velocity[0] = speed;
    return client.Send(channels_.wind, command);
  }

  /// The answer to raw `bytes` published on WIND.
  ack_t AnswerTo(const std::vector<uint8_t>& bytes) {
    acks_.clear();
    bus_.Publish(channels_.wind, bytes.data(), bytes.size());
    clock_.Step(server_);
    EXPECT_EQ(acks_.size(), 1u);
    return acks_.empty() ? ack_t{} : acks_.back();
  }

  int64_t Refused(CommandAuthenticator::Refusal refusal) const {
    return server_.stats().commands_refused[static_cast<size_t>(refusal)];
  }
  sim::Vec3 Wind() const { return server_.session().scene().wind.velocity; }

  testing::SimulatedClock clock_;
  Bus bus_;
  Channels channels_;
  Server server_;
  std::vector<uint8_t> sent_;
  std::vector<ack_t> acks_;
  std::vector<applied_command_t> applied_;
};

TEST_F(SignedCommandIntakeTest, ASignedCommandIsTakenAndTheJournalNamesItsSender) {
  EXPECT_EQ(server_.authentication(), "HMAC-SHA-256, keys ops");
  const CommandOutcome outcome = SendWind(CommandSigner(Key("ops", 7)), 6);
  ASSERT_EQ(outcome.result, CommandOutcome::kAccepted) << outcome.reason;
  EXPECT_EQ(Wind(), (sim::Vec3{6, 0, 0}));
  ASSERT_EQ(applied_.size(), 1u);
  EXPECT_EQ(applied_[0].key_id, "ops");
  EXPECT_EQ(applied_[0].client_id.rfind("flagctl-", 0), 0u);
}

TEST_F(SignedCommandIntakeTest, UnsignedUnknownAndForgedCommandsAreRefusedWithTheirReason) {
  const sim::Vec3 before = Wind();
  const auto expect_refused = [&](const CommandOutcome& outcome, const std::string& kind) {
    EXPECT_EQ(outcome.result, CommandOutcome::kRejected);
    EXPECT_EQ(outcome.reason.rfind(kind + ": ", 0), 0u) << outcome.reason;
  };
  expect_refused(SendWind(CommandSigner(), 6), "unsigned");
  expect_refused(SendWind(CommandSigner(Key("stranger", 7)), 6), "unknown key");
  expect_refused(SendWind(CommandSigner(Key("ops", 8)), 6), "bad MAC");  // the right name, not the key
  EXPECT_EQ(Wind(), before);
  using Refusal = CommandAuthenticator::Refusal;
  EXPECT_EQ(Refused(Refusal::kUnsigned), 1);
  EXPECT_EQ(Refused(Refusal::kUnknownKey), 1);
  EXPECT_EQ(Refused(Refusal::kBadMac), 1);
  EXPECT_EQ(server_.stats().commands_accepted + server_.stats().commands_rejected, 0);
  EXPECT_TRUE(applied_.empty());
}

TEST_F(SignedCommandIntakeTest, ACommandSentAgainFromTheBusIsReplayedAndAnOldOneStale) {
  ASSERT_EQ(SendWind(CommandSigner(Key("ops", 7)), 6).result, CommandOutcome::kAccepted);
  const std::vector<uint8_t> captured = sent_;
  ASSERT_EQ(SendWind(CommandSigner(Key("ops", 7)), 2).result, CommandOutcome::kAccepted);
  const ack_t replayed = AnswerTo(captured);  // the 6 m/s wind, captured and sent again
  EXPECT_FALSE(replayed.accepted);
  EXPECT_EQ(replayed.reason.rfind("replayed: ", 0), 0u) << replayed.reason;
  EXPECT_EQ(Wind(), (sim::Vec3{2, 0, 0}));

  wind_command_t old{};
  old.client_id = "old-client";
  old.sequence = 1;
  old.velocity[0] = 9;
  CommandSigner(Key("ops", 7)).Stamp(channels_.wind, old);
  old.utime -= 60'000'000;  // a minute ago: signed again with that time
  old.key_id = "ops";
  const Mac mac = MacOf(Key("ops", 7), channels_.wind, old);
  std::copy(mac.begin(), mac.end(), old.mac);
  const ack_t stale = AnswerTo(testing::Encode(old));
  EXPECT_FALSE(stale.accepted);
  EXPECT_EQ(stale.reason.rfind("stale: its time stamp is 60.0 s behind", 0), 0u) << stale.reason;
  EXPECT_EQ(Wind(), (sim::Vec3{2, 0, 0}));
  EXPECT_EQ(Refused(CommandAuthenticator::Refusal::kReplayed), 1);
  EXPECT_EQ(Refused(CommandAuthenticator::Refusal::kStale), 1);
  EXPECT_EQ(applied_.size(), 2u);
}

TEST_F(SignedCommandIntakeTest, AReadersQuestionNeedsNoSignatureButAKeyframeRequestDoes) {
  CommandClient reader(bus_, channels_, 5.0, {}, clock_.Reader());
  reader.WhileWaiting([this] { clock_.Step(server_); });
  refresh_request_t question{};
  question.tables_only = true;
  EXPECT_EQ(reader.Send(channels_.refresh, question).result, CommandOutcome::kAccepted);
  const CommandOutcome keyframe = reader.Send(channels_.refresh, refresh_request_t{});
  EXPECT_EQ(keyframe.result, CommandOutcome::kRejected);
  EXPECT_EQ(keyframe.reason.rfind("unsigned: ", 0), 0u) << keyframe.reason;
  // The question is neither a command taken nor one refused.
  EXPECT_EQ(server_.stats().commands_accepted, 0);
  EXPECT_EQ(Refused(CommandAuthenticator::Refusal::kUnsigned), 1);
}

TEST_F(SignedCommandIntakeTest, AFloodOfForgeriesIsCountedAndFewAreAnswered) {
  constexpr int kForgeries = 20000, kBatch = 200;
  wind_command_t forged{};
  forged.client_id = "forger";
  forged.velocity[0] = 30;
  const auto flood = [&](int first) {
    for (int sent = 0; sent < kForgeries; sent += kBatch) {
      for (int k = 0; k < kBatch; ++k) {
        forged.sequence = first + sent + k;
        CommandSigner(Key("ops", 1)).Stamp(channels_.wind, forged);
        const std::vector<uint8_t> bytes = testing::Encode(forged);
        bus_.Publish(channels_.wind, bytes.data(), bytes.size());
      }
      clock_.Step(server_);
    }
  };  // over 100 steps: 0.2 s of the server's clock
  flood(0);
  EXPECT_EQ(Refused(CommandAuthenticator::Refusal::kBadMac), kForgeries);
  // Answers are limited per second of the server's clock.
  EXPECT_EQ(acks_.size(), size_t(CommandIntake::kRefusalAnswersPerSecond));
  const double next_second = clock_.now() + 1;
  clock_.StepUntil(server_, [&] { return clock_.now() >= next_second; });
  flood(kForgeries);
  EXPECT_EQ(Refused(CommandAuthenticator::Refusal::kBadMac), 2 * kForgeries);
  EXPECT_EQ(acks_.size(), size_t(2 * CommandIntake::kRefusalAnswersPerSecond));
  EXPECT_EQ(Wind(), Scene{}.wind.velocity);
  EXPECT_EQ(SendWind(CommandSigner(Key("ops", 7)), 3).result, CommandOutcome::kAccepted);
}

}  // namespace
}  // namespace flagsim
