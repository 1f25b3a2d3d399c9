// What the gateway offers a Foxglove WebSocket client: channels (server to client), services
// (request and response) and the topics a client may publish on. Schemas are the JSON files in
// schemas/, embedded at build time; docs/live-view.md describes each.
//
// Each flagd the gateway serves has a slot, and its channels and services a number in it:
//
//   id = slot * kSlotStride + base        (base: ChannelId or ServiceId below)
//   topic = path + base topic              (path "" for a single server: /flag/tiles;
//                                           "/ALPHA_" for one of many: /ALPHA_/flag/tiles)
//
// A single-server gateway's server is slot 0, so its ids are the bases themselves; the
// gateway's own channels are in slot 0 too. Ids never change within a gateway's run, so a
// client may cache them across reconnections.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

namespace flagsim::gateway {

constexpr uint32_t kSlotStride = 16;

enum ChannelId : uint32_t {
  // each server's
  kTilesChannel = 1,
  kImageChannel,
  kSceneChannel,
  kStateChannel,
  kStatusChannel,
  kParamsChannel,
  kTimelineChannel,
  kCameraChannel,
  kAcksChannel,
  // the gateway's own (slot 0)
  kGatewayStatusChannel,
  kServersChannel,
};
constexpr uint32_t kServerChannelCount = kAcksChannel;
constexpr uint32_t kChannelCount = kServersChannel;  ///< a single-server gateway's

enum ServiceId : uint32_t {
  kWindService = 1,
  kSetService,
  kCameraService,
  kKeyframeService,
  kRefreshService,
  kRecordService,
  kTimeService,
  kDesignService,
};
constexpr uint32_t kServiceCount = kDesignService;

struct ChannelInfo {
  ChannelId id;
  std::string_view topic;
  std::string_view encoding;
  std::string_view schema_name;
  std::string_view schema_encoding;
  std::string_view schema_file;  ///< stem in schemas/
};

struct ServiceInfo {
  ServiceId id;
  std::string_view name;
  std::string_view type;
  std::string_view request_schema;   ///< stem in schemas/
  std::string_view response_schema;  ///< stem in schemas/
};

/// Every channel and service by its base id, a server's and the gateway's own.
const std::vector<ChannelInfo>& AdvertisedChannels();
const std::vector<ServiceInfo>& AdvertisedServices();
const ChannelInfo* FindChannel(uint32_t base);
const ServiceInfo* FindService(uint32_t base);

/// The slot and the base of an id (channel or service).
inline uint32_t SlotOf(uint32_t id) { return id / kSlotStride; }
inline uint32_t BaseOf(uint32_t id) { return id % kSlotStride; }
inline uint32_t IdIn(uint32_t slot, uint32_t base) { return slot * kSlotStride + base; }
inline bool IsGatewayChannel(uint32_t id) { return id == kGatewayStatusChannel || id == kServersChannel; }

/// The protocol's advertisements: the channels and the services of the server in `slot` whose
/// topics start with `path`, and the gateway's own channels.
nlohmann::json ServerChannelsJson(uint32_t slot, const std::string& path);
nlohmann::json ServerServicesJson(uint32_t slot, const std::string& path);
nlohmann::json GatewayChannelsJson();
/// Their ids, for withdrawing them.
std::vector<uint32_t> ServerChannelIds(uint32_t slot);
std::vector<uint32_t> ServerServiceIds(uint32_t slot);

/// The greeting's first message.
std::string ServerInfoMessage(const std::string& name, const std::string& session_id);

/// The text of schemas/STEM.json (or .txt); throws std::out_of_range for an unknown stem.
std::string_view Schema(std::string_view stem);

}  // namespace flagsim::gateway
