// What the gateway's tests share: a client without a socket (FakeClient), a small scene and the
// gateway's options on a simulated clock.
#pragma once

#include <gtest/gtest.h>

#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "client/gateway/foxglove_wire.hpp"
#include "client/gateway/gateway.hpp"
#include "server/scene/scene.hpp"
#include "tests/service/simulated_clock.hpp"

namespace flagsim::gateway::testing {

using nlohmann::json;

inline uint32_t U32(const std::string& bytes, size_t at) {
  uint32_t value = 0;
  for (int k = 3; k >= 0; --k) value = value << 8 | uint8_t(bytes[at + k]);
  return value;
}

/// A client without a socket: what the protocol gives it, sorted by kind.
class FakeClient : public GatewayClient {
 public:
  explicit FakeClient(Gateway& gateway) : gateway_(gateway), id_(gateway.Attach(this)) {
    protocol_.emplace(gateway, id_);
    protocol_->Start("test", "1");
  }
  ~FakeClient() override {
    protocol_.reset();
    gateway_.Detach(id_);
  }
  ClientProtocol& protocol() override { return *protocol_; }
  void Wake() override {}
  std::string address() const override { return "test"; }

  /// Takes everything waiting, as a socket that keeps up would.
  void Read() {
    while (std::optional<Outgoing> message = protocol_->Next()) {
      const std::string bytes = message->head + (message->body ? *message->body : "");
      if (!message->binary) {
        texts.push_back(json::parse(bytes));
      } else if (bytes[0] == kMessageData) {
        data[U32(bytes, 1)].push_back(bytes.substr(13));
      } else if (bytes[0] == kServiceCallResponse) {
        const uint32_t encoding = U32(bytes, 9);
        responses[U32(bytes, 5)] = json::parse(bytes.substr(13 + encoding));
      }
    }
  }
  void Send(const json& message) { protocol_->OnText(message.dump()); }
  void Subscribe(uint32_t channel) {
    Send({{"op", "subscribe"}, {"subscriptions", {{{"id", channel}, {"channelId", channel}}}}});
  }
  void Call(uint32_t service, uint32_t call, const std::string& request) {
    std::string frame(1, char(kServiceCallRequest));
    AppendU32(&frame, service);
    AppendU32(&frame, call);
    AppendU32(&frame, 4);
    protocol_->OnBinary(frame + "json" + request);
  }
  /// The texts with `op`, and `id` if given.
  std::vector<json> Texts(const std::string& op, const std::string& id = "") const {
    std::vector<json> found;
    for (const json& text : texts) {
      if (text["op"] == op && (id.empty() || text.value("id", "") == id)) found.push_back(text);
    }
    return found;
  }
  json LatestJson(uint32_t channel) const { return json::parse(data.at(channel).back()); }

  std::vector<json> texts;
  std::map<uint32_t, std::vector<std::string>> data;  ///< by subscription id (= channel id here)
  std::map<uint32_t, json> responses;                 ///< by call id

 private:
  Gateway& gateway_;
  int id_;
  std::optional<ClientProtocol> protocol_;
};

inline Scene SmallScene() {
  Scene scene;
  scene.camera.width = 320;
  scene.camera.height = 192;
  return scene;
}

/// The gateway's options in these tests: its recordings in the test's directory, its clock the
/// server's simulated one.
inline GatewayOptions OptionsOn(const flagsim::testing::SimulatedClock& clock) {
  GatewayOptions options;
  options.record_directory = ::testing::TempDir() + "/gateway_test_recordings";
  options.clock = clock.Reader();
  return options;
}

}  // namespace flagsim::gateway::testing
