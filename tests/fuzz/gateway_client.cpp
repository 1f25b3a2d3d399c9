#include "tests/fuzz/gateway_client.hpp"

#include <nlohmann/json.hpp>

#include "client/gateway/foxglove_wire.hpp"
#include "client/gateway/gateway_catalog.hpp"
#include "tests/fuzz/command_server.hpp"

namespace flagsim::fuzz {
namespace {

using nlohmann::json;

uint32_t U32(const std::string& bytes, size_t at) {
  uint32_t value = 0;
  for (int k = 3; k >= 0; --k) value = value << 8 | uint8_t(bytes[at + size_t(k)]);
  return value;
}

void CheckText(const std::string& text) {
  const json message = json::parse(text, nullptr, false);
  Require(
      !message.is_discarded() && message.is_object() && message.contains("op") && message["op"].is_string(),
      "the gateway sent a text message that is not a JSON object with an op", text.substr(0, 200));
}

void CheckBinary(const std::string& bytes) {
  const bool data = !bytes.empty() && bytes[0] == gateway::kMessageData && bytes.size() >= 13;
  const bool response = !bytes.empty() && bytes[0] == gateway::kServiceCallResponse && bytes.size() >= 13 &&
                        U32(bytes, 9) <= bytes.size() - 13;
  Require(data || response, "the gateway sent a binary message a client cannot parse");
  if (response && bytes.substr(13, U32(bytes, 9)) == "json") {
    Require(!json::parse(bytes.substr(13 + 4), nullptr, false).is_discarded(),
            "the gateway answered a service call with JSON that does not parse");
  }
}

}  // namespace

ReadingClient::ReadingClient(gateway::Gateway& gateway) : gateway_(gateway), id_(gateway.Attach(this)) {
  protocol_.emplace(gateway, id_);
  protocol_->Start("fuzz", "1");
}

ReadingClient::~ReadingClient() {
  protocol_.reset();
  gateway_.Detach(id_);
}

void ReadingClient::SubscribeAll() {
  json subscriptions = json::array();
  for (const gateway::ChannelInfo& channel : gateway::AdvertisedChannels())
    subscriptions.push_back({{"id", channel.id}, {"channelId", channel.id}});
  protocol_->OnText(json{{"op", "subscribe"}, {"subscriptions", subscriptions}}.dump());
}

void ReadingClient::ReadAll() {
  while (std::optional<gateway::Outgoing> message = protocol_->Next()) {
    const std::string bytes = message->head + (message->body ? *message->body : "");
    if (message->binary) {
      CheckBinary(bytes);
    } else {
      CheckText(bytes);
    }
  }
}

}  // namespace flagsim::fuzz
