// Commands without blocking: resent with one sequence number until answered, answered once,
// and timed out on the caller's clock.
#include "client/gateway/command_relay.hpp"

#include <gtest/gtest.h>

#include "flagsim/wind_command_t.hpp"
#include "messages/checked_decode.hpp"

namespace flagsim::gateway {
namespace {

class CommandRelayTest : public ::testing::Test {
 protected:
  CommandRelayTest() : bus_("memq://"), relay_(bus_, "gateway-test", 2.0) {
    bus_.Subscribe("WIND", [this](const std::string&, const uint8_t* data, size_t size) {
      std::string error;
      const auto command = wire::CheckedDecode<wind_command_t>(data, size, 1 << 16, &error);
      ASSERT_TRUE(command) << error;
      sent_.push_back(*command);
    });
  }

  ack_t Ack(int64_t sequence, bool accepted) {
    ack_t ack{};
    ack.client_id = "gateway-test";
    ack.sequence = sequence;
    ack.accepted = accepted;
    ack.reason = accepted ? "" : "gust: 3 is out of range";
    ack.step = 42;
    return ack;
  }

  Bus bus_;
  CommandRelay relay_;
  std::vector<wind_command_t> sent_;
};

TEST_F(CommandRelayTest, ResendsWithTheSameSequenceUntilAnswered) {
  std::vector<CommandOutcome> outcomes;
  const int64_t sequence =
      relay_.Send("WIND", wind_command_t{}, 100.0,
                  [&](const CommandOutcome& outcome, int64_t) { outcomes.push_back(outcome); });
  relay_.Tick(100.2);
  relay_.Tick(100.5);
  relay_.Tick(100.9);
  relay_.Tick(101.0);
  bus_.HandleAll();
  ASSERT_EQ(sent_.size(), 3u) << "at 100.0, 100.5 and 101.0";
  for (const wind_command_t& command : sent_) {
    EXPECT_EQ(command.sequence, sequence);
    EXPECT_EQ(command.client_id, "gateway-test");
  }
  relay_.OnAck(Ack(sequence, true));
  relay_.OnAck(Ack(sequence, true));  // a second answer to a retry: ignored
  ASSERT_EQ(outcomes.size(), 1u);
  EXPECT_EQ(outcomes[0].result, CommandOutcome::kAccepted);
  EXPECT_EQ(outcomes[0].step, 42);
  EXPECT_EQ(relay_.pending(), 0u);
}

TEST_F(CommandRelayTest, ARejectionCarriesTheReasonAndOthersAnswersAreNotOurs) {
  std::vector<CommandOutcome> outcomes;
  const int64_t sequence =
      relay_.Send("WIND", wind_command_t{}, 0.0,
                  [&](const CommandOutcome& outcome, int64_t) { outcomes.push_back(outcome); });
  ack_t theirs = Ack(sequence, true);
  theirs.client_id = "someone-else";
  relay_.OnAck(theirs);
  EXPECT_TRUE(outcomes.empty());
  relay_.OnAck(Ack(sequence, false));
  ASSERT_EQ(outcomes.size(), 1u);
  EXPECT_EQ(outcomes[0].result, CommandOutcome::kRejected);
  EXPECT_EQ(outcomes[0].reason, "gust: 3 is out of range");
}

TEST_F(CommandRelayTest, NoAnswerWithinTheTimeoutIsReportedOnceAndMaySendAgain) {
  int calls = 0;
  relay_.Send("WIND", wind_command_t{}, 0.0, [&](const CommandOutcome& outcome, int64_t) {
    EXPECT_EQ(outcome.result, CommandOutcome::kNoAnswer);
    if (++calls == 1) relay_.Send("WIND", wind_command_t{}, 2.0, [](const CommandOutcome&, int64_t) {});
  });
  relay_.Tick(1.99);
  EXPECT_EQ(calls, 0);
  relay_.Tick(2.0);
  relay_.Tick(2.1);
  EXPECT_EQ(calls, 1);
  EXPECT_EQ(relay_.pending(), 1u) << "the callback's own command";
  EXPECT_EQ(relay_.NextDue(), 2.5);
}

}  // namespace
}  // namespace flagsim::gateway
