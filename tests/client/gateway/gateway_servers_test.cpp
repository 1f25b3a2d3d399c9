// One gateway for several servers: two flagd on one in-process bus (memq://) with their own
// prefixes, found by their STATUS and offered under /PREFIX, steered apart, withdrawn when they
// fall silent and offered again when they come back.
#include <gtest/gtest.h>

#include <functional>
#include <memory>

#include "client/gateway/gateway.hpp"
#include "client/gateway/gateway_parameters.hpp"
#include "server/service/server.hpp"
#include "tests/client/gateway/fake_client.hpp"
#include "tests/client/gateway/tile_update_reader.hpp"
#include "tests/service/simulated_clock.hpp"

namespace flagsim::gateway {
namespace {

using nlohmann::json;
using testing::FakeClient;
using testing::OptionsOn;
using testing::SmallScene;

class GatewayServersTest : public ::testing::Test {
 protected:
  GatewayServersTest()
      : bus_("memq://"),
        alpha_(std::make_unique<Server>(bus_, alpha_channels_, SmallScene(), clock_.ServerOnIt())),
        beta_(std::make_unique<Server>(bus_, beta_channels_, SmallScene(), clock_.ServerOnIt())),
        gateway_(bus_, ServerSelection::Many({}), OptionsOn(clock_)),
        client_(gateway_) {}

  /// Runs the servers there are, the bus and the gateway until `done`, within a generous bound of
  /// wall time; false if it never came.
  bool RunUntil(const std::function<bool()>& done) {
    const double give_up = MonotonicSeconds() + 60;
    while (MonotonicSeconds() < give_up) {
      std::vector<Server*> running;
      for (Server* server : {alpha_.get(), beta_.get()}) {
        if (server) running.push_back(server);
      }
      clock_.Step(running);
      bus_.HandleAll();
      gateway_.Tick();
      client_.Read();
      if (done()) return true;
    }
    return false;
  }

  /// The topics the client has been advertised and not withdrawn, by channel id.
  std::map<uint32_t, std::string> Topics() const {
    std::map<uint32_t, std::string> topics;
    for (const json& text : client_.texts) {
      if (text["op"] == "advertise") {
        for (const json& channel : text["channels"]) topics[channel["id"]] = channel["topic"];
      }
      if (text["op"] == "unadvertise") {
        for (const json& id : text["channelIds"]) topics.erase(id.get<uint32_t>());
      }
    }
    return topics;
  }
  /// The id of the channel advertised as `topic`; 0 if none.
  uint32_t ChannelOf(const std::string& topic) const {
    for (const auto& [id, name] : Topics()) {
      if (name == topic) return id;
    }
    return 0;
  }
  /// The id of the service advertised as `name` (the newest advertisement); 0 if none.
  uint32_t ServiceOf(const std::string& name) const {
    uint32_t found = 0;
    for (const json& text : client_.Texts("advertiseServices")) {
      for (const json& service : text["services"]) {
        if (service["name"] == name) found = service["id"];
      }
    }
    return found;
  }
  bool BothOffered() const { return ChannelOf("/ALPHA_/flag/tiles") && ChannelOf("/BETA_/flag/tiles"); }
  json Servers() const { return client_.LatestJson(kServersChannel)["servers"]; }

  flagsim::testing::SimulatedClock clock_;
  Bus bus_;
  const Channels alpha_channels_{"ALPHA_"}, beta_channels_{"BETA_"};  // a server keeps them by reference
  std::unique_ptr<Server> alpha_, beta_;
  Gateway gateway_;
  FakeClient client_;
};

TEST_F(GatewayServersTest, EachServerHeardIsOfferedUnderItsPrefix) {
  client_.Read();
  EXPECT_EQ(ChannelOf("/flag/tiles"), 0u) << "a gateway of several servers has no plain topics";
  EXPECT_EQ(ChannelOf("/gateway/servers"), kServersChannel);
  EXPECT_EQ(ChannelOf("/ALPHA_/flag/tiles"), 0u) << "nothing is offered before its STATUS is heard";
  ASSERT_TRUE(RunUntil([&] { return BothOffered(); }));
  for (const std::string prefix : {"ALPHA_", "BETA_"}) {
    const uint32_t tiles = ChannelOf("/" + prefix + "/flag/tiles");
    EXPECT_EQ(BaseOf(tiles), kTilesChannel);
    EXPECT_EQ(ChannelOf("/" + prefix + "/flag/acks"), IdIn(SlotOf(tiles), kAcksChannel));
    EXPECT_EQ(ServiceOf("/" + prefix + "/flag/wind"), IdIn(SlotOf(tiles), kWindService));
    EXPECT_EQ(ServiceOf("/" + prefix + "/flag/record"), IdIn(SlotOf(tiles), kRecordService));
  }
  EXPECT_NE(SlotOf(ChannelOf("/ALPHA_/flag/tiles")), SlotOf(ChannelOf("/BETA_/flag/tiles")));
}

TEST_F(GatewayServersTest, TwoPicturesSideBySideAreEachTheirServers) {
  ASSERT_TRUE(RunUntil([&] { return BothOffered(); }));
  const uint32_t alpha = ChannelOf("/ALPHA_/flag/tiles"), beta = ChannelOf("/BETA_/flag/tiles");
  client_.Subscribe(alpha);
  client_.Subscribe(beta);
  client_.Call(ServiceOf("/BETA_/flag/camera"), 1, R"({"operation": "size", "width": 256, "height": 160})");
  testing::TileUpdateReader alpha_reader, beta_reader;  // each update checked against its frame's hash
  size_t alpha_applied = 0, beta_applied = 0;
  ASSERT_TRUE(RunUntil([&] {
    for (; client_.data[alpha].size() > alpha_applied; ++alpha_applied)
      EXPECT_EQ(alpha_reader.Apply(client_.data[alpha][alpha_applied]), "");
    for (; client_.data[beta].size() > beta_applied; ++beta_applied)
      EXPECT_EQ(beta_reader.Apply(client_.data[beta][beta_applied]), "");
    return alpha_applied >= 5 && beta_applied >= 5 && beta_reader.width() == 256;
  }));
  EXPECT_EQ(alpha_reader.width(), 320) << "the camera move went to BETA_ only";
  EXPECT_EQ(alpha_reader.frame_id(), gateway_.Frame(alpha)->frame_id);
  EXPECT_EQ(beta_reader.frame_id(), gateway_.Frame(beta)->frame_id);
}

TEST_F(GatewayServersTest, ParametersAndServicesReachTheirOwnServerOnly) {
  ASSERT_TRUE(RunUntil([&] { return BothOffered(); }));
  client_.Send({{"op", "subscribeParameterUpdates"}, {"parameterNames", {"/BETA_/stiffness"}}});
  client_.Send({{"op", "setParameters"},
                {"id", "s"},
                {"parameters", {{{"name", "/BETA_/stiffness"}, {"value", 1234}}}}});
  client_.Call(ServiceOf("/ALPHA_/flag/wind"), 2, R"({"velocity": [8, 0, 0]})");
  ASSERT_TRUE(
      RunUntil([&] { return !client_.Texts("parameterValues", "s").empty() && client_.responses.count(2); }));
  EXPECT_TRUE(client_.responses[2]["accepted"]) << client_.responses[2];
  EXPECT_EQ(alpha_->session().scene().wind.velocity, (sim::Vec3{8, 0, 0}));
  EXPECT_NE(beta_->session().scene().wind.velocity, (sim::Vec3{8, 0, 0}));
  EXPECT_EQ(beta_->session().scene().sim.forces.stiffness, 1234);
  EXPECT_NE(alpha_->session().scene().sim.forces.stiffness, 1234);
  const json values = client_.Texts("parameterValues", "s").back()["parameters"];
  ASSERT_EQ(values.size(), 1u) << values;
  EXPECT_EQ(values[0]["name"], "/BETA_/stiffness");
  EXPECT_EQ(values[0]["value"], 1234);
  bool followed = false;  // the update to those following the name, without an id
  for (const json& text : client_.Texts("parameterValues")) {
    for (const json& value : text["parameters"])
      followed |= !text.contains("id") && value["name"] == "/BETA_/stiffness";
  }
  EXPECT_TRUE(followed);

  client_.Send(
      {{"op", "setParameters"},
       {"id", "mixed"},
       {"parameters",
        {{{"name", "/BETA_/damping"}, {"value", 0.1}}, {{"name", "/ALPHA_/damping"}, {"value", 0.1}}}}});
  ASSERT_TRUE(RunUntil([&] { return !client_.Texts("status", "setParameters:mixed").empty(); }));
  EXPECT_EQ(
      client_.Texts("status", "setParameters:mixed")[0]["message"],
      "setParameters: '/ALPHA_/damping' is not a parameter of /BETA_; set each server's parameters in a "
      "message of their own");
  client_.Send({{"op", "getParameters"}, {"id", "all"}, {"parameterNames", json::array()}});
  ASSERT_TRUE(RunUntil([&] { return !client_.Texts("parameterValues", "all").empty(); }));
  const json all = client_.Texts("parameterValues", "all")[0]["parameters"];
  size_t alpha = 0, beta = 0;
  for (const json& value : all) {
    alpha += ParameterNameOf("/ALPHA_", value["name"]).has_value();
    beta += ParameterNameOf("/BETA_", value["name"]).has_value();
  }
  EXPECT_EQ(alpha + beta, all.size());
  EXPECT_EQ(alpha, beta);
  EXPECT_GT(alpha, 20u);
}

TEST_F(GatewayServersTest, AClientPublishesOnAServersTopicsOnly) {
  ASSERT_TRUE(RunUntil([&] { return BothOffered(); }));
  client_.Send({{"op", "advertise"},
                {"channels",
                 {{{"id", 1}, {"topic", "/flag/wind"}, {"encoding", "json"}},
                  {{"id", 2}, {"topic", "/BETA_/flag/wind"}, {"encoding", "json"}}}}});
  client_.Read();
  ASSERT_EQ(client_.Texts("status").size(), 1u) << "the plain topic is refused, BETA_'s taken";
  EXPECT_NE(client_.Texts("status")[0]["message"].get<std::string>().find("'/flag/wind'"), std::string::npos);
}

TEST_F(GatewayServersTest, TheServerListSaysWhatEachServerShows) {
  client_.Subscribe(kServersChannel);
  ASSERT_TRUE(RunUntil([&] {
    if (!client_.data.count(kServersChannel)) return false;
    const json servers = Servers();
    return servers.size() == 2 && servers[0]["width"] == 320 && servers[1]["width"] == 320 &&
           servers[0]["scene"] != "" && servers[1]["scene"] != "";
  }));
  const json servers = Servers();
  EXPECT_EQ(servers[0]["prefix"], "ALPHA_");
  EXPECT_EQ(servers[0]["path"], "/ALPHA_");
  EXPECT_EQ(servers[1]["prefix"], "BETA_");
  EXPECT_TRUE(servers[1]["live"]);
  EXPECT_EQ(servers[1]["height"], 192);
  const auto& model = beta_->session().simulation().model();
  EXPECT_EQ(servers[1]["scene"], std::to_string(model.cols) + " x " + std::to_string(model.rows) +
                                     " nodes, 1.5 x 1 m, nordic_cross")
      << servers[1];
}

TEST_F(GatewayServersTest, AServerThatFallsSilentIsWithdrawnAndOfferedAgainWhenItReturns) {
  ASSERT_TRUE(RunUntil([&] { return BothOffered(); }));
  const uint32_t tiles = ChannelOf("/ALPHA_/flag/tiles");
  const uint32_t wind = ServiceOf("/ALPHA_/flag/wind");
  client_.Subscribe(tiles);
  ASSERT_TRUE(RunUntil([&] { return client_.data[tiles].size() >= 2; }));
  alpha_.reset();
  const double stopped = clock_.now();
  ASSERT_TRUE(RunUntil([&] { return ChannelOf("/ALPHA_/flag/tiles") == 0; }));
  EXPECT_GE(clock_.now() - stopped, Gateway::kSilence - 1.0) << "withdrawn only after its silence";
  EXPECT_NE(ChannelOf("/BETA_/flag/tiles"), 0u);
  const std::vector<json> withdrawn = client_.Texts("unadvertiseServices");
  ASSERT_EQ(withdrawn.size(), 1u);
  EXPECT_NE(std::find(withdrawn[0]["serviceIds"].begin(), withdrawn[0]["serviceIds"].end(), wind),
            withdrawn[0]["serviceIds"].end());
  client_.Call(wind, 3, R"({"velocity": [1, 0, 0]})");
  client_.Read();
  ASSERT_FALSE(client_.Texts("serviceCallFailure").empty());
  EXPECT_EQ(client_.Texts("serviceCallFailure")[0]["message"],
            "service " + std::to_string(wind) + " is not advertised");

  alpha_ = std::make_unique<Server>(bus_, alpha_channels_, SmallScene(), clock_.ServerOnIt());
  ASSERT_TRUE(RunUntil([&] { return ChannelOf("/ALPHA_/flag/tiles") != 0; }));
  EXPECT_EQ(ChannelOf("/ALPHA_/flag/tiles"), tiles) << "the same ids as before";
  const size_t before = client_.data[tiles].size();
  client_.Subscribe(tiles);  // its subscription went with it
  ASSERT_TRUE(RunUntil([&] { return client_.data[tiles].size() > before; }));
}

TEST(GatewayServerList, OnlyTheServersAskedForAreOffered) {
  flagsim::testing::SimulatedClock clock;
  Bus bus("memq://");
  const Channels alpha_channels("ALPHA_"), beta_channels("BETA_");
  Server alpha(bus, alpha_channels, SmallScene(), clock.ServerOnIt());
  Server beta(bus, beta_channels, SmallScene(), clock.ServerOnIt());
  Gateway gateway(bus, ServerSelection::Many({"BETA_"}), OptionsOn(clock));
  const double give_up = MonotonicSeconds() + 60;
  while (gateway.server(1) == nullptr && MonotonicSeconds() < give_up) {
    clock.Step({&alpha, &beta});
    bus.HandleAll();
    gateway.Tick();
  }
  for (int pass = 0; pass < 1000; ++pass) {  // two seconds more of both servers' STATUS
    clock.Step({&alpha, &beta});
    bus.HandleAll();
    gateway.Tick();
  }
  ASSERT_NE(gateway.server(1), nullptr);
  EXPECT_EQ(gateway.server(1)->channels().prefix, "BETA_");
  EXPECT_EQ(gateway.server(2), nullptr) << "ALPHA_ was not asked for";
}

}  // namespace
}  // namespace flagsim::gateway
