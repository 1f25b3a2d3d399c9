// What a client's protocol asks of the gateway: the channels' messages, the picture, and the
// requests it passes on. ClientProtocol knows only this, so it is tested and fuzzed against the
// gateway without a socket, and the gateway's hub may change behind it.
#pragma once

#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>

#include "client/gateway/channel_feed.hpp"
#include "client/gateway/frame_mirror.hpp"

namespace flagsim::gateway {

class ClientHub {
 public:
  enum class ChannelKind { kNone, kTiles, kAcks, kFeed };

  virtual ~ClientHub() = default;

  /// The advertisements of everything offered now (a new client's greeting after serverInfo).
  virtual std::vector<std::string> Advertisements() const = 0;
  /// What channel `id` is; kNone if it is not offered now.
  virtual ChannelKind KindOf(uint32_t id) const = 0;
  /// The messages of a kFeed or kAcks channel; null if it is not offered now.
  virtual ChannelFeed* Feed(uint32_t id) = 0;
  /// The newest whole frame of a kTiles channel; null if none (yet).
  virtual std::shared_ptr<const MirroredFrame> Frame(uint32_t id) const = 0;
  /// The service a client may publish on as `topic` (a command service's name); nullopt if none.
  virtual std::optional<uint32_t> ServiceForTopic(std::string_view topic) const = 0;

  virtual void SubscribersChanged(uint32_t id, int delta) = 0;
  virtual void CallService(int client, uint32_t service, uint32_t call, std::string_view encoding,
                           std::string_view payload) = 0;
  virtual void PublishCommand(int client, uint32_t service, std::string_view payload) = 0;
  virtual void GetParameters(int client, const nlohmann::json& names, const std::string& id) = 0;
  virtual void SetParameters(int client, const nlohmann::json& parameters, const std::string& id) = 0;
  /// A client message that was not the protocol (counted in /gateway/status).
  virtual void CountProtocolError() = 0;
};

}  // namespace flagsim::gateway
