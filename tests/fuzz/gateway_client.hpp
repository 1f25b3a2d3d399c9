// A client of the gateway without a socket (the transport's side of client/gateway/gateway.hpp),
// for the fuzz targets: it takes everything its protocol has for it, as a socket that keeps up
// would, and checks each message as a Foxglove client reads it:
//   text     a JSON object with a string "op"
//   binary   Message Data (13-byte head) or Service Call Response (13 bytes and its encoding)
// A message that is neither aborts the run (libFuzzer reports it as a crash).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "client/gateway/client_protocol.hpp"
#include "client/gateway/gateway.hpp"

namespace flagsim::fuzz {

class ReadingClient : public gateway::GatewayClient {
 public:
  explicit ReadingClient(gateway::Gateway& gateway);
  ~ReadingClient() override;

  gateway::ClientProtocol& protocol() override { return *protocol_; }
  void Wake() override {}
  std::string address() const override { return "fuzz"; }

  /// Subscribes to every channel the gateway advertises (subscription id = channel id).
  void SubscribeAll();
  /// Takes every message waiting, checking each.
  void ReadAll();

 private:
  gateway::Gateway& gateway_;
  int id_;
  std::optional<gateway::ClientProtocol> protocol_;
};

}  // namespace flagsim::fuzz
