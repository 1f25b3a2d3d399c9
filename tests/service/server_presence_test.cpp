// Telling servers on one prefix apart: the ids in STATUS, STATE and ACK, and the count of other
// servers heard, on an in-process bus (memq://) with a clock the test moves.
#include "server/service/server_presence.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>

#include "client/command_client.hpp"
#include "flagsim/state_t.hpp"
#include "flagsim/status_t.hpp"
#include "server/service/server.hpp"
#include "tests/messages/message_fixtures.hpp"
#include "tests/service/simulated_clock.hpp"

namespace flagsim {
namespace {

class ServerPresenceTest : public ::testing::Test {
 protected:
  ServerPresenceTest() : bus_("memq://"), presence_(bus_, channels_, [this] { return now_; }) {}

  /// A STATUS as another server with `id` would publish it, handled at once.
  void HearStatusOf(int64_t id) {
    status_t status{};
    status.server_id = id;
    bus_.Publish(channels_.status, status);
    bus_.HandleAll();
  }

  Bus bus_;
  Channels channels_;
  double now_ = 100;
  ServerPresence presence_;
};

TEST_F(ServerPresenceTest, ItsIdIsPositiveAndDiffersFromAnothers) {
  ServerPresence other(bus_, channels_);
  EXPECT_GT(presence_.id(), 0);
  EXPECT_GT(other.id(), 0);
  EXPECT_NE(presence_.id(), other.id());
}

TEST_F(ServerPresenceTest, AnotherServersStatusCountsUntilItGoesQuiet) {
  EXPECT_EQ(presence_.others(), 0);
  HearStatusOf(presence_.id());  // its own: not another
  HearStatusOf(0);               // no live server's
  EXPECT_EQ(presence_.others(), 0);
  HearStatusOf(42);
  HearStatusOf(42);
  EXPECT_EQ(presence_.others(), 1);
  now_ += 2;
  HearStatusOf(43);
  EXPECT_EQ(presence_.others(), 2);
  now_ += ServerPresence::kForgetAfter - 1;  // 42 last heard kForgetAfter + 1 s ago
  EXPECT_EQ(presence_.others(), 1);
  now_ += 2;
  EXPECT_EQ(presence_.others(), 0);
}

// Garbage on STATUS is no other server, and a server counts it as dropped (STATUS
// messages_dropped), as it counts undecodable commands.
TEST(ServerPresence, GarbageOnStatusIsCountedAsDroppedAndIgnored) {
  Bus bus("memq://");
  const Channels channels;
  testing::SimulatedClock clock;
  Server server(bus, channels, Scene{}, clock.ServerOnIt());
  clock.Step(server);
  const int64_t dropped_before = server.stats().messages_dropped;
  const std::vector<uint8_t> garbage = {1, 2, 3, 4, 5, 6, 7, 8, 9};
  bus.Publish(channels.status, garbage.data(), garbage.size());
  bus.Publish(channels.status, garbage.data(), 3);
  clock.Step(server);
  EXPECT_EQ(server.stats().messages_dropped, dropped_before + 2);
  EXPECT_EQ(server.presence().others(), 0);
}

TEST_F(ServerPresenceTest, AFloodOfForgedIdsIsBounded) {
  for (int64_t id = 1; id <= 1000; ++id) HearStatusOf(id);
  EXPECT_EQ(presence_.others(), int(ServerPresence::kMaxRemembered));
}

// A server's STATE, STATUS and ACK carry its id, and its ACK and STATUS the others it hears.
TEST(ServerIds, TheServerSaysWhoItIsAndWhomElseItHears) {
  Bus bus("memq://");
  Channels channels;
  testing::SimulatedClock clock;
  ServerOptions options = clock.ServerOnIt();
  options.duration = 0.2;
  Server server(bus, channels, Scene{}, options);
  std::vector<state_t> states;
  std::vector<status_t> statuses;
  bus.Subscribe(channels.state, [&](const std::string&, const uint8_t* data, size_t size) {
    states.emplace_back().decode(data, 0, int(size));
  });
  bus.Subscribe(channels.status, [&](const std::string&, const uint8_t* data, size_t size) {
    statuses.emplace_back().decode(data, 0, int(size));
  });
  status_t other{};
  other.server_id = server.presence().id() + 1;
  bus.Publish(channels.status, other);
  CommandClient client(bus, channels, 5.0, {}, clock.Reader());
  client.WhileWaiting([&] { clock.Step(server); });
  const CommandOutcome outcome = client.Send(channels.wind, testing::SomeWindCommand());
  ASSERT_EQ(outcome.result, CommandOutcome::kAccepted) << outcome.reason;
  EXPECT_EQ(outcome.server_id, server.presence().id());
  EXPECT_EQ(outcome.other_servers, 1);
  clock.StepUntil(server, [&] { return server.session().simulation().state().time >= options.duration; });
  std::atomic<bool> stop{false};
  server.Run(stop);  // at its duration: the last STATE and STATUS
  ASSERT_FALSE(states.empty());
  for (const state_t& state : states) EXPECT_EQ(state.server_id, server.presence().id());
  const auto own = std::find_if(statuses.rbegin(), statuses.rend(),
                                [&](const status_t& s) { return s.server_id == server.presence().id(); });
  ASSERT_NE(own, statuses.rend());
  EXPECT_EQ(own->other_servers, 1);
}

}  // namespace
}  // namespace flagsim
