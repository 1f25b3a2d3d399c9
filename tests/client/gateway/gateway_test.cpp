// The gateway with a real flagd server on an in-process bus (memq://) and clients without
// sockets: what they are sent, how their requests reach the server, and what bad requests do.
#include "client/gateway/gateway.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <random>

#include "client/gateway/foxglove_wire.hpp"
#include "flagsim/checkpoint_t.hpp"
#include "messages/event_log_reader.hpp"
#include "server/service/server.hpp"
#include "tests/client/gateway/base64.hpp"
#include "tests/client/gateway/fake_client.hpp"
#include "tests/client/gateway/tile_update_reader.hpp"
#include "tests/common/test_images.hpp"
#include "tests/service/simulated_clock.hpp"

namespace flagsim::gateway {
namespace {

using nlohmann::json;
using testing::FakeClient;
using testing::OptionsOn;
using testing::SmallScene;

// The server steps on a simulated clock, one step per pass of the test's loop; the frame stage
// and the paced publisher are real threads, so conditions on frames are waited for.
class GatewayTest : public ::testing::Test {
 protected:
  GatewayTest()
      : bus_("memq://"),
        server_(bus_, channels_, SmallScene(), clock_.ServerOnIt()),
        gateway_(bus_, ServerSelection::One(channels_.prefix), OptionsOn(clock_)),
        client_(gateway_) {}

  /// Runs the server, the bus and the gateway until `done` (the client reading all along),
  /// within a generous bound of wall time; false if it never came.
  bool RunUntil(const std::function<bool()>& done, FakeClient* reader = nullptr) {
    reader = reader ? reader : &client_;
    const double give_up = MonotonicSeconds() + 60;
    while (MonotonicSeconds() < give_up) {
      clock_.Step(server_);
      bus_.HandleAll();
      gateway_.Tick();
      reader->Read();
      if (done()) return true;
    }
    return false;
  }
  bool HasData(uint32_t channel, size_t count = 1) const {
    return client_.data.count(channel) > 0 && client_.data.at(channel).size() >= count;
  }

  flagsim::testing::SimulatedClock clock_;
  Bus bus_;
  Channels channels_;
  Server server_;
  Gateway gateway_;
  FakeClient client_;
};

TEST_F(GatewayTest, ANewClientHearsWhoWeAreWhatWeSendAndWhatWeServe) {
  client_.Read();
  ASSERT_GE(client_.texts.size(), 3u);
  EXPECT_EQ(client_.texts[0]["op"], "serverInfo");
  EXPECT_EQ(client_.texts[1]["op"], "advertise");
  EXPECT_EQ(client_.texts[1]["channels"].size(), kChannelCount);
  EXPECT_EQ(client_.texts[1]["channels"][kImageChannel - 1]["schemaName"], "foxglove.CompressedImage");
  EXPECT_EQ(client_.texts[2]["op"], "advertiseServices");
  EXPECT_EQ(client_.texts[2]["services"].size(), 8u);
  for (const json& channel : client_.texts[1]["channels"]) {
    if (channel["encoding"] == "json") {
      EXPECT_FALSE(json::parse(channel["schema"].get<std::string>(), nullptr, false).is_discarded())
          << channel;
    }
  }
}

TEST_F(GatewayTest, TheServersStreamsArriveAsJson) {
  for (uint32_t channel : {kStateChannel, kStatusChannel, kParamsChannel, kTimelineChannel, kCameraChannel}) {
    client_.Subscribe(channel);
  }
  ASSERT_TRUE(RunUntil([&] {
    return HasData(kStateChannel) && HasData(kStatusChannel) && HasData(kParamsChannel) &&
           HasData(kTimelineChannel) && HasData(kCameraChannel);
  }));
  const json state = client_.LatestJson(kStateChannel);
  EXPECT_EQ(state["cols"], server_.session().simulation().model().cols);
  EXPECT_EQ(state["state_hash"].get<std::string>().size(), 16u);
  EXPECT_GT(state["tip_from_pole"].get<double>(), 0.5) << "a flag in a breeze stands out from its pole";
  EXPECT_TRUE(state.contains("kinetic_energy"));
  EXPECT_EQ(client_.LatestJson(kStatusChannel)["integrator"], "symplectic_euler");
  bool found = false;
  const json params = client_.LatestJson(kParamsChannel);
  for (const json& row : params["parameters"]) {
    if (row["name"] == "stiffness") {
      found = true;
      EXPECT_EQ(row["kind"], "real");
      EXPECT_EQ(row["value"].get<double>(), server_.session().scene().sim.forces.stiffness);
    }
  }
  EXPECT_TRUE(found);
  EXPECT_TRUE(client_.LatestJson(kTimelineChannel)["keys"].is_array());
  EXPECT_EQ(client_.LatestJson(kCameraChannel)["width"], 320);
}

TEST_F(GatewayTest, TheTilesAssembleToTheServersFramesExactly) {
  client_.Subscribe(kTilesChannel);
  testing::TileUpdateReader reader;
  size_t applied = 0;
  ASSERT_TRUE(RunUntil([&] {
    for (; HasData(kTilesChannel, applied + 1); ++applied) {
      EXPECT_EQ(reader.Apply(client_.data[kTilesChannel][applied]), "") << "update " << applied;
      EXPECT_EQ(reader.keyframe(), applied == 0);
    }
    return applied >= 5;
  }));
  EXPECT_EQ(reader.frame_id(), gateway_.frame()->frame_id);
}

TEST_F(GatewayTest, ASlowClientSkipsToTheNewestFrameInsteadOfQueueing) {
  FakeClient slow(gateway_);
  slow.Subscribe(kTilesChannel);
  client_.Subscribe(kTilesChannel);
  ASSERT_TRUE(RunUntil([&] { return gateway_.frame() != nullptr; }));
  slow.Read();  // the keyframe
  ASSERT_EQ(slow.data[kTilesChannel].size(), 1u);
  testing::TileUpdateReader reader;
  ASSERT_EQ(reader.Apply(slow.data[kTilesChannel][0]), "");
  ASSERT_TRUE(RunUntil([&] { return HasData(kTilesChannel, 8); }));
  slow.Read();
  ASSERT_EQ(slow.data[kTilesChannel].size(), 2u) << "one update, to the newest frame";
  EXPECT_EQ(reader.Apply(slow.data[kTilesChannel][1]), "");
  EXPECT_EQ(reader.frame_id(), gateway_.frame()->frame_id);
  EXPECT_GE(slow.protocol().counters().frames_skipped, 5u);
}

TEST_F(GatewayTest, ACommandServiceIsAnsweredWithTheServersAck) {
  client_.Call(kWindService, 7, R"({"velocity": [9, 0, 1], "gust": 0.1})");
  ASSERT_TRUE(RunUntil([&] { return client_.responses.count(7) > 0; }));
  const json& result = client_.responses[7];
  EXPECT_TRUE(result["accepted"]) << result;
  EXPECT_EQ(result["channel"], "WIND");
  EXPECT_GE(result["step"].get<int64_t>(), 0);
  EXPECT_EQ(server_.session().scene().wind.velocity, (sim::Vec3{9, 0, 1}));
}

TEST_F(GatewayTest, TheClockServicePausesStepsAndResumesTheServer) {
  client_.Call(kTimeService, 1, R"({"operation": "pause"})");
  ASSERT_TRUE(RunUntil([&] { return client_.responses.count(1) > 0; }));
  EXPECT_TRUE(client_.responses[1]["accepted"]) << client_.responses[1];
  EXPECT_EQ(client_.responses[1]["channel"], "TIME");
  EXPECT_TRUE(server_.session().paused());
  const int64_t held = server_.session().simulation().state().step;
  client_.Call(kTimeService, 2, R"({"operation": "step", "steps": 4})");
  ASSERT_TRUE(RunUntil([&] { return client_.responses.count(2) > 0; }));
  ASSERT_TRUE(RunUntil([&] { return server_.session().steps_owed() == 0; }));
  EXPECT_EQ(server_.session().simulation().state().step, held + 4);
  client_.Call(kTimeService, 3, R"({"operation": "rewind"})");
  ASSERT_TRUE(RunUntil([&] { return !client_.Texts("serviceCallFailure").empty(); }));
  EXPECT_EQ(client_.Texts("serviceCallFailure").back()["message"],
            "operation: 'rewind' is not one; allowed pause, resume, step");
  client_.Call(kTimeService, 4, R"({"operation": "resume"})");
  ASSERT_TRUE(RunUntil([&] { return client_.responses.count(4) > 0; }));
  EXPECT_FALSE(server_.session().paused());
}

TEST_F(GatewayTest, ARejectedCommandSaysWhyAndChangesNothing) {
  const sim::Vec3 before = server_.session().scene().wind.velocity;
  client_.Call(kWindService, 8, R"({"velocity": [9, 0, 1], "gust": 3})");
  ASSERT_TRUE(RunUntil([&] { return client_.responses.count(8) > 0; }));
  EXPECT_FALSE(client_.responses[8]["accepted"]);
  EXPECT_TRUE(client_.responses[8]["answered"]);
  EXPECT_EQ(client_.responses[8]["reason"].get<std::string>().rfind("gust:", 0), 0u) << client_.responses[8];
  EXPECT_EQ(server_.session().scene().wind.velocity, before);
}

// A server with keys takes the page's commands when the gateway signs them (flagctl serve
// --key-file), and refuses them, with the reason, when it does not.
TEST(GatewayWithKeys, TheServerTakesWhatTheGatewaySigns) {
  CommandKey key;
  key.name = "ops";
  key.secret.fill(3);
  Bus bus("memq://");
  Channels channels;
  flagsim::testing::SimulatedClock clock;
  ServerOptions keyed = clock.ServerOnIt();
  keyed.command_keys = {key};
  Server server(bus, channels, SmallScene(), keyed);
  GatewayOptions signing = OptionsOn(clock), plain = OptionsOn(clock);
  signing.signer = CommandSigner(key);
  const ServerSelection one = ServerSelection::One(channels.prefix);
  Gateway signed_gateway(bus, one, signing), plain_gateway(bus, one, plain);
  FakeClient signed_page(signed_gateway), plain_page(plain_gateway);
  signed_page.Call(kWindService, 1, R"({"velocity": [7, 0, 0]})");
  plain_page.Call(kWindService, 2, R"({"velocity": [3, 0, 0]})");
  const double give_up = clock.now() + 30;  // the relay gives up after its timeout, on this clock
  while (clock.now() < give_up &&
         (signed_page.responses.count(1) == 0 || plain_page.responses.count(2) == 0)) {
    clock.Step(server);
    bus.HandleAll();
    signed_gateway.Tick();
    plain_gateway.Tick();
    signed_page.Read();
    plain_page.Read();
  }
  ASSERT_EQ(signed_page.responses.count(1), 1u);
  ASSERT_EQ(plain_page.responses.count(2), 1u);
  EXPECT_TRUE(signed_page.responses[1]["accepted"]) << signed_page.responses[1];
  EXPECT_FALSE(plain_page.responses[2]["accepted"]);
  EXPECT_EQ(plain_page.responses[2]["reason"].get<std::string>().rfind("unsigned: ", 0), 0u)
      << plain_page.responses[2];
  EXPECT_EQ(server.session().scene().wind.velocity, (sim::Vec3{7, 0, 0}));
}

TEST_F(GatewayTest, RequestsThatAreNoCommandFailTheCallWithTheReason) {
  client_.Call(kCameraService, 1, "not json");
  client_.Call(kCameraService, 2, R"({"operation": "spin"})");
  client_.Call(99, 3, "{}");
  client_.Read();
  const auto failures = client_.Texts("serviceCallFailure");
  ASSERT_EQ(failures.size(), 3u);
  EXPECT_EQ(failures[0]["message"], "/flag/camera: the request is not JSON");
  EXPECT_EQ(failures[1]["callId"], 2);
  EXPECT_NE(failures[1]["message"].get<std::string>().find("'spin' is not one"), std::string::npos);
  EXPECT_EQ(failures[2]["message"], "service 99 is not advertised");
}

TEST_F(GatewayTest, SetParametersAnswersWithTheValuesInForceAndRejectionsWithTheReason) {
  client_.Send(
      {{"op", "setParameters"}, {"id", "a"}, {"parameters", {{{"name", "stiffness"}, {"value", 1500}}}}});
  ASSERT_TRUE(RunUntil([&] { return !client_.Texts("parameterValues", "a").empty(); }));
  EXPECT_EQ(client_.Texts("parameterValues", "a")[0]["parameters"][0],
            json({{"name", "stiffness"}, {"value", 1500.0}}));
  EXPECT_EQ(server_.session().scene().sim.forces.stiffness, 1500);

  client_.Send(
      {{"op", "setParameters"}, {"id", "b"}, {"parameters", {{{"name", "stiffness"}, {"value", -5}}}}});
  ASSERT_TRUE(RunUntil([&] { return !client_.Texts("parameterValues", "b").empty(); }));
  const auto statuses = client_.Texts("status", "setParameters:b");
  ASSERT_EQ(statuses.size(), 1u);
  EXPECT_EQ(statuses[0]["level"], ClientProtocol::kError);
  EXPECT_EQ(statuses[0]["message"].get<std::string>().rfind("stiffness:", 0), 0u) << statuses[0];
  EXPECT_EQ(client_.Texts("parameterValues", "b")[0]["parameters"][0]["value"], 1500.0) << "unchanged";
  EXPECT_EQ(server_.session().scene().sim.forces.stiffness, 1500);
}

TEST_F(GatewayTest, ParameterUpdatesGoToClientsThatFollowThem) {
  client_.Send({{"op", "subscribeParameterUpdates"}, {"parameterNames", {"damping"}}});
  client_.Call(kSetService, 1, R"({"parameters": {"damping": 0.2, "friction": 0.05}})");
  ASSERT_TRUE(RunUntil([&] { return client_.responses.count(1) > 0; }));
  ASSERT_TRUE(client_.responses[1]["accepted"]) << client_.responses[1];
  bool saw_damping = false;
  for (const json& values : client_.Texts("parameterValues")) {
    for (const json& value : values["parameters"]) {
      EXPECT_EQ(value["name"], "damping") << "friction is not followed";
      saw_damping |= value["value"] == 0.2;
    }
  }
  EXPECT_TRUE(saw_damping);
}

// A client follows at most 64 parameter names of at most 64 characters: a message that would
// pass either limit is answered with the limit and follows none of its names.
TEST_F(GatewayTest, AClientFollowsOnlySoManyParameterNames) {
  json names = {"damping"};
  for (size_t k = 1; k < ClientProtocol::kMaxFollowedParameters; ++k)
    names.push_back("name" + std::to_string(k));
  client_.Send({{"op", "subscribeParameterUpdates"}, {"parameterNames", names}});
  client_.Send({{"op", "subscribeParameterUpdates"}, {"parameterNames", {"one_too_many"}}});
  client_.Send(
      {{"op", "subscribeParameterUpdates"}, {"parameterNames", {std::string(70000, 'x'), "friction"}}});
  client_.Read();
  const std::vector<json> statuses = client_.Texts("status");
  ASSERT_EQ(statuses.size(), 2u);
  EXPECT_EQ(
      statuses[0]["message"],
      "subscribeParameterUpdates: 65 names would be followed; allowed at most 64 per client (the parameter "
      "table has fewer; no names follows them all); none of this message's names followed");
  EXPECT_EQ(statuses[1]["message"],
            "subscribeParameterUpdates: '" + std::string(64, 'x') +
                "...' is 70000 characters long; allowed parameter names of up to 64 characters; none of this "
                "message's names followed");
  client_.Call(kSetService, 1, R"({"parameters": {"damping": 0.2, "friction": 0.05}})");
  ASSERT_TRUE(RunUntil([&] { return client_.responses.count(1) > 0; }));
  ASSERT_TRUE(RunUntil([&] { return !client_.Texts("parameterValues").empty(); }));
  for (const json& values : client_.Texts("parameterValues")) {
    for (const json& value : values["parameters"])
      EXPECT_EQ(value["name"], "damping") << "friction was refused";
  }
}

TEST_F(GatewayTest, ClientsMayPublishCommandsOnTheCommandTopics) {
  client_.Subscribe(kAcksChannel);
  client_.Send(
      {{"op", "advertise"},
       {"channels", {{{"id", 5}, {"topic", "/flag/camera"}, {"encoding", "json"}, {"schemaName", "x"}}}}});
  std::string frame(1, char(kClientMessageData));
  AppendU32(&frame, 5);
  client_.protocol().OnBinary(frame + R"({"operation": "orbit", "degrees": 20, "degrees2": 5})");
  ASSERT_TRUE(RunUntil([&] { return HasData(kAcksChannel); }));
  const json ack = client_.LatestJson(kAcksChannel);
  EXPECT_EQ(ack["channel"], "CAMERA");
  EXPECT_TRUE(ack["accepted"]) << ack;

  client_.Send(
      {{"op", "advertise"},
       {"channels", {{{"id", 6}, {"topic", "/somewhere"}, {"encoding", "json"}, {"schemaName", "x"}}}}});
  client_.Read();
  EXPECT_NE(client_.texts.back()["message"].get<std::string>().find("not a topic to publish on"),
            std::string::npos);
}

// A client may advertise at most 32 channels to publish on; the 33rd is refused with the limit,
// and those it has go on working.
TEST_F(GatewayTest, AClientMayAdvertiseOnlySoManyChannels) {
  json channels = json::array();
  for (uint32_t id = 1; id <= ClientProtocol::kMaxClientChannels + 1; ++id)
    channels.push_back({{"id", id}, {"topic", "/flag/camera"}, {"encoding", "json"}, {"schemaName", "x"}});
  client_.Send({{"op", "advertise"}, {"channels", channels}});
  client_.Read();
  const std::vector<json> statuses = client_.Texts("status");
  ASSERT_EQ(statuses.size(), 1u);
  EXPECT_EQ(statuses[0]["message"], "advertise: at most 32 client channels");
  EXPECT_EQ(statuses[0]["level"], ClientProtocol::kError);
  client_.Send({{"op", "advertise"}, {"channels", {channels[0]}}});  // one it has: advertised again
  client_.Read();
  EXPECT_EQ(client_.Texts("status").size(), 1u);
  client_.Subscribe(kAcksChannel);
  std::string frame(1, char(kClientMessageData));
  AppendU32(&frame, ClientProtocol::kMaxClientChannels);  // the last one taken
  client_.protocol().OnBinary(frame + R"({"operation": "orbit", "degrees": 5, "degrees2": 0})");
  ASSERT_TRUE(RunUntil([&] { return HasData(kAcksChannel); }));
  EXPECT_TRUE(client_.LatestJson(kAcksChannel)["accepted"]) << client_.LatestJson(kAcksChannel);
  frame.resize(1);
  AppendU32(&frame, ClientProtocol::kMaxClientChannels + 1);  // the one refused
  client_.protocol().OnBinary(frame + R"({"operation": "orbit", "degrees": 5, "degrees2": 0})");
  client_.Read();
  EXPECT_EQ(client_.Texts("status").back()["message"], "Client Message Data on channel 33, never advertised");
}

TEST_F(GatewayTest, HostileMessagesAreAnsweredAndLeaveTheGatewayServing) {
  client_.Read();
  const size_t before = client_.texts.size();
  std::mt19937 random(7);
  const std::vector<std::string> texts = {
      "",
      "{",
      "[]",
      "null",
      R"({"op": 5})",
      R"({"op": "subscribe"})",
      R"({"op": "subscribe", "subscriptions": 7})",
      R"({"op": "subscribe", "subscriptions": [{"id": -1, "channelId": 1}, {"id": 1, "channelId": 4000000000}]})",
      R"({"op": "setParameters", "parameters": [{"value": 1}]})",
      R"({"op": "getParameters", "parameterNames": {}})",
      R"({"op": "fetchAsset", "uri": "file:///etc/passwd", "requestId": 1})",
      std::string(1000, '['),
      std::string(100000, '[') + std::string(100000, ']')};
  for (const std::string& text : texts) client_.protocol().OnText(text);
  for (int trial = 0; trial < 2000; ++trial) {
    std::string bytes(random() % 64, '\0');
    for (char& c : bytes) c = char(random());
    client_.protocol().OnBinary(bytes);
  }
  client_.Read();
  EXPECT_GT(client_.texts.size(), before + texts.size() - 1);
  EXPECT_GT(gateway_.counters().protocol_errors, texts.size());
  client_.Call(kWindService, 77, R"({"velocity": [5, 0, 0]})");
  ASSERT_TRUE(RunUntil([&] { return client_.responses.count(77) > 0; }));
  EXPECT_TRUE(client_.responses[77]["accepted"]);
}

TEST_F(GatewayTest, AClientMayHaveOnlySoManyCommandsWaitingForAnswers) {
  const int calls = Gateway::kMaxCommandsInFlight + 5;
  for (int call = 1; call <= calls; ++call) client_.Call(kWindService, call, R"({"velocity": [5, 0, 0]})");
  client_.Read();
  const auto refused = client_.Texts("serviceCallFailure");
  ASSERT_EQ(refused.size(), 5u);
  EXPECT_NE(refused[0]["message"].get<std::string>().find("commands waiting"), std::string::npos);
  ASSERT_TRUE(RunUntil([&] { return client_.responses.size() == size_t(Gateway::kMaxCommandsInFlight); }));
  client_.Call(kWindService, 100, R"({"velocity": [6, 0, 0]})");
  ASSERT_TRUE(RunUntil([&] { return client_.responses.count(100) > 0; }));
  EXPECT_TRUE(client_.responses[100]["accepted"]) << "answered ones make room";
}

TEST_F(GatewayTest, TheImageAndTheSceneAreForFoxglove) {
  client_.Subscribe(kImageChannel);
  client_.Subscribe(kSceneChannel);
  ASSERT_TRUE(RunUntil([&] { return HasData(kImageChannel) && HasData(kSceneChannel); }));
  const json image = client_.LatestJson(kImageChannel);
  EXPECT_EQ(image["format"], "jpeg");
  EXPECT_EQ(image["data"].get<std::string>().substr(0, 4), "/9j/") << "base64 of a JPEG's FF D8 FF";
  const json scene = client_.LatestJson(kSceneChannel);
  const auto& model = server_.session().simulation().model();
  const json& flag = scene["entities"][0];
  EXPECT_EQ(flag["id"], "flag");
  EXPECT_EQ(flag["triangles"][0]["points"].size(), size_t(model.cols * model.rows));
  EXPECT_EQ(flag["triangles"][0]["indices"].size(), size_t(6 * (model.cols - 1) * (model.rows - 1)));
  EXPECT_EQ(scene["entities"][1]["cylinders"].size(), 1u);
}

bool IsRefreshCheckpoint(const uint8_t* data, size_t size) {
  checkpoint_t checkpoint;
  return checkpoint.decode(data, 0, int(size)) == int(size) && checkpoint.reason == "refresh";
}

TEST_F(GatewayTest, ARecordingIsALogOfTheBusToDownload) {
  // The gateway's own keyframe request at its start answered first: the recording asks again.
  bool answered = false;
  bus_.Subscribe(channels_.checkpoint, [&answered](const std::string&, const uint8_t* data, size_t size) {
    answered |= IsRefreshCheckpoint(data, size);
  });
  ASSERT_TRUE(RunUntil([&answered] { return answered; }));
  client_.Call(kRecordService, 1, R"({"action": "start"})");
  client_.Read();
  ASSERT_TRUE(client_.responses[1]["recording"]) << client_.responses[1];
  const std::string name = client_.responses[1]["file"];
  EXPECT_FALSE(gateway_.RecordingFile(name)) << "not while it is being written";
  const double until = clock_.now() + 0.5;  // 30 STATEs, PARAMS and STATUS, at least
  ASSERT_TRUE(RunUntil([&] { return clock_.now() > until; }));
  client_.Call(kRecordService, 2, R"({"action": "stop"})");
  client_.Read();
  const json& stopped = client_.responses[2];
  EXPECT_FALSE(stopped["recording"]);
  EXPECT_EQ(stopped["url"], "/recordings/" + name);
  EXPECT_GT(stopped["events"].get<int64_t>(), 10);
  const std::optional<std::string> path = gateway_.RecordingFile(name);
  ASSERT_TRUE(path);
  EventLogReader log(*path);
  LogEvent event;
  int refreshes = 0;  // the answer to the recording's own keyframe request
  while (log.Next(&event))
    refreshes +=
        event.channel == channels_.checkpoint && IsRefreshCheckpoint(event.data.data(), event.data.size());
  EXPECT_EQ(log.events(), stopped["events"].get<int64_t>());
  EXPECT_EQ(refreshes, 1) << "a recording starts with a whole frame and a checkpoint";
  EXPECT_FALSE(gateway_.RecordingFile("../" + name));
  EXPECT_FALSE(gateway_.RecordingFile("/etc/passwd"));
}

TEST_F(GatewayTest, AnImageUploadedInPartsBecomesTheDesign) {
  std::vector<uint8_t> rgba = flagsim::testing::SolidRgba(120, 40, 30, 90, 160);
  for (size_t i = 3; i < rgba.size(); i += 8) rgba[i] = 0;  // every other pixel transparent
  const std::vector<uint8_t> png = flagsim::testing::PngBytes(120, 40, rgba);
  const size_t half = png.size() / 2;
  const auto part = [&](size_t offset, size_t length) {
    return json{{"name", "striped.png"},
                {"size", png.size()},
                {"offset", offset},
                {"data", testing::Base64({png.begin() + long(offset), png.begin() + long(offset + length)})}}
        .dump();
  };
  client_.Call(kDesignService, 1, part(0, half));
  ASSERT_TRUE(RunUntil([&] { return client_.responses.count(1) > 0; }));
  EXPECT_EQ(client_.responses[1]["reason"],
            "held " + std::to_string(half) + " of " + std::to_string(png.size()) + " bytes");
  client_.Call(kDesignService, 2, part(half, png.size() - half));
  ASSERT_TRUE(RunUntil([&] { return client_.responses.count(2) > 0; }));
  EXPECT_TRUE(client_.responses[2]["accepted"]) << client_.responses[2];
  EXPECT_EQ(client_.responses[2]["channel"], "DESIGN");
  const Scene& scene = server_.session().scene();
  EXPECT_EQ(scene.service.design, render::FlagDesign::kImage);
  ASSERT_TRUE(scene.service.design_file);
  EXPECT_EQ(scene.service.design_file->bytes, png);
  EXPECT_DOUBLE_EQ(scene.sim.width, 3 * scene.sim.height);

  client_.Call(kDesignService, 3, R"({"name": "tricolour"})");
  ASSERT_TRUE(RunUntil([&] { return client_.responses.count(3) > 0; }));
  EXPECT_EQ(client_.responses[3]["channel"], "PARAM");
  EXPECT_EQ(server_.session().scene().service.design, render::FlagDesign::kTricolour);
}

}  // namespace
}  // namespace flagsim::gateway
