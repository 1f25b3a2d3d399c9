// A flagd restarted on the same channels, with the gateway running on: viewers follow the new
// server, whose frame ids start again from 0.
#include <gtest/gtest.h>

#include <functional>

#include "client/gateway/gateway.hpp"
#include "server/service/server.hpp"
#include "tests/client/gateway/fake_client.hpp"
#include "tests/client/gateway/tile_update_reader.hpp"
#include "tests/service/simulated_clock.hpp"

namespace flagsim::gateway {
namespace {

using testing::FakeClient;
using testing::OptionsOn;
using testing::SmallScene;

// A server restarted on the same channels numbers its frames from 0 again. The gateway hears a
// new server id on STATE and forgets the old server's frame: a client watching all along is
// taken to the new server's frames (before, the new tiles were taken for older ones and skipped
// until the new ids passed the old, minutes for a long-running server).
TEST(GatewayRestart, ClientsFollowANewServerWhoseFramesStartAgain) {
  flagsim::testing::SimulatedClock clock;
  Bus bus("memq://");
  Channels channels;
  Gateway gateway(bus, ServerSelection::One(channels.prefix), OptionsOn(clock));
  FakeClient client(gateway);
  client.Subscribe(kTilesChannel);
  testing::TileUpdateReader reader;
  size_t applied = 0;
  const auto run_until = [&](Server& server, const std::function<bool()>& done) {
    const double give_up = MonotonicSeconds() + 60;
    while (MonotonicSeconds() < give_up) {
      clock.Step(server);
      bus.HandleAll();
      gateway.Tick();
      client.Read();
      for (; client.data.count(kTilesChannel) && client.data[kTilesChannel].size() > applied; ++applied) {
        EXPECT_EQ(reader.Apply(client.data[kTilesChannel][applied]), "") << "update " << applied;
      }
      if (done()) return true;
    }
    return false;
  };
  int64_t last_of_first = -1;
  {
    Server first(bus, channels, SmallScene(), clock.ServerOnIt());
    ASSERT_TRUE(run_until(first, [&] { return reader.frame_id() >= 20; }));
    last_of_first = reader.frame_id();
  }
  Server second(bus, channels, SmallScene(), clock.ServerOnIt());
  ASSERT_TRUE(run_until(second, [&] { return reader.frame_id() < last_of_first; }))
      << "the client still shows frame " << reader.frame_id() << " of the old server";
  EXPECT_EQ(gateway.server(0)->counters().server_restarts, 1u);
  ASSERT_TRUE(run_until(second, [&] { return reader.frame_id() >= 3; }));
  EXPECT_EQ(reader.frame_id(), gateway.frame()->frame_id) << "the client is on the new server's newest frame";
}

}  // namespace
}  // namespace flagsim::gateway
