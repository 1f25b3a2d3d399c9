// What the gateway offers a Foxglove WebSocket client: its channels (server to client), its
// services (request and response) and the topics a client may publish on. Ids are fixed, so a
// client may cache them across reconnections. Schemas are the JSON files in schemas/,
// embedded at build time. docs/live-view.md describes each.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace flagsim::gateway {

enum ChannelId : uint32_t {
  kTilesChannel = 1,
  kImageChannel,
  kSceneChannel,
  kStateChannel,
  kStatusChannel,
  kParamsChannel,
  kTimelineChannel,
  kCameraChannel,
  kAcksChannel,
  kGatewayStatusChannel,
};
constexpr uint32_t kChannelCount = kGatewayStatusChannel;

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

const std::vector<ChannelInfo>& AdvertisedChannels();
const std::vector<ServiceInfo>& AdvertisedServices();
const ChannelInfo* FindChannel(uint32_t id);
const ServiceInfo* FindService(uint32_t id);
/// The service whose name is `topic`: client-published topics are the command services' names.
const ServiceInfo* ServiceForTopic(std::string_view topic);

/// The protocol's JSON messages that introduce the gateway to a new client.
std::string ServerInfoMessage(const std::string& name, const std::string& session_id);
std::string AdvertiseMessage();
std::string AdvertiseServicesMessage();

/// The text of schemas/STEM.json (or .txt); throws std::out_of_range for an unknown stem.
std::string_view Schema(std::string_view stem);

}  // namespace flagsim::gateway
