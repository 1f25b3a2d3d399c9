#include "client/gateway/gateway_catalog.hpp"

#include <nlohmann/json.hpp>
#include <stdexcept>

namespace flagsim::gateway {

// Generated from schemas/ by cmake/embed_text.cmake.
const std::vector<std::pair<std::string_view, std::string_view>>& GatewaySchemas();

namespace {
using nlohmann::json;

/// A schema as sent: JSON ones without their layout's whitespace, text ones as written.
std::string CompactSchema(std::string_view stem) {
  const json parsed = json::parse(Schema(stem), nullptr, false);
  return parsed.is_discarded() ? std::string(Schema(stem)) : parsed.dump();
}

}  // namespace

const std::vector<ChannelInfo>& AdvertisedChannels() {
  static const std::vector<ChannelInfo> channels = {
      {kTilesChannel, "/flag/tiles", "flagsim.tiles", "flagsim.TileUpdate", "text", "tile_update"},
      {kImageChannel, "/flag/image", "json", "foxglove.CompressedImage", "jsonschema", "compressed_image"},
      {kSceneChannel, "/flag/scene", "json", "foxglove.SceneUpdate", "jsonschema", "scene_update"},
      {kStateChannel, "/flag/state", "json", "flagsim.StateSummary", "jsonschema", "state_summary"},
      {kStatusChannel, "/flag/status", "json", "flagsim.Status", "jsonschema", "status"},
      {kParamsChannel, "/flag/params", "json", "flagsim.Params", "jsonschema", "params"},
      {kTimelineChannel, "/flag/timeline", "json", "flagsim.Timeline", "jsonschema", "timeline"},
      {kCameraChannel, "/flag/camera", "json", "flagsim.Camera", "jsonschema", "camera"},
      {kAcksChannel, "/flag/acks", "json", "flagsim.Ack", "jsonschema", "ack"},
      {kGatewayStatusChannel, "/gateway/status", "json", "flagsim.GatewayStatus", "jsonschema",
       "gateway_status"},
  };
  return channels;
}

const std::vector<ServiceInfo>& AdvertisedServices() {
  static const std::vector<ServiceInfo> services = {
      {kWindService, "/flag/wind", "flagsim.Wind", "wind_request", "command_result"},
      {kSetService, "/flag/set", "flagsim.Set", "set_request", "command_result"},
      {kCameraService, "/flag/camera", "flagsim.Camera", "camera_request", "command_result"},
      {kKeyframeService, "/flag/keyframe", "flagsim.Keyframe", "keyframe_request", "command_result"},
      {kRefreshService, "/flag/refresh", "flagsim.Refresh", "refresh_request", "command_result"},
      {kRecordService, "/flag/record", "flagsim.Record", "record_request", "record_result"},
      {kTimeService, "/flag/time", "flagsim.Time", "time_request", "command_result"},
      {kDesignService, "/flag/design", "flagsim.Design", "design_request", "command_result"},
  };
  return services;
}

const ChannelInfo* FindChannel(uint32_t id) {
  return id >= 1 && id <= AdvertisedChannels().size() ? &AdvertisedChannels()[id - 1] : nullptr;
}

const ServiceInfo* FindService(uint32_t id) {
  return id >= 1 && id <= AdvertisedServices().size() ? &AdvertisedServices()[id - 1] : nullptr;
}

const ServiceInfo* ServiceForTopic(std::string_view topic) {
  for (const ServiceInfo& service : AdvertisedServices()) {
    if (service.name == topic && service.id != kRecordService) return &service;
  }
  return nullptr;
}

std::string_view Schema(std::string_view stem) {
  for (const auto& [name, text] : GatewaySchemas()) {
    if (name == stem) return text;
  }
  throw std::out_of_range("no schema " + std::string(stem));
}

std::string ServerInfoMessage(const std::string& name, const std::string& session_id) {
  return json{{"op", "serverInfo"},
              {"name", name},
              {"capabilities", {"clientPublish", "parameters", "parametersSubscribe", "services"}},
              {"supportedEncodings", {"json"}},
              {"metadata", {{"protocol_notes", "see docs/live-view.md of flagsim"}}},
              {"sessionId", session_id}}
      .dump();
}

// Both made once: the channels and services never change, and every client connecting is sent them.
std::string AdvertiseMessage() {
  static const std::string message = [] {
    json channels = json::array();
    for (const ChannelInfo& channel : AdvertisedChannels()) {
      channels.push_back({{"id", channel.id},
                          {"topic", channel.topic},
                          {"encoding", channel.encoding},
                          {"schemaName", channel.schema_name},
                          {"schemaEncoding", channel.schema_encoding},
                          {"schema", CompactSchema(channel.schema_file)}});
    }
    return json{{"op", "advertise"}, {"channels", channels}}.dump();
  }();
  return message;
}

std::string AdvertiseServicesMessage() {
  static const std::string message = [] {
    json services = json::array();
    for (const ServiceInfo& service : AdvertisedServices()) {
      const auto definition = [](std::string_view stem) {
        return json{{"encoding", "json"},
                    {"schemaName", json::parse(Schema(stem)).value("title", std::string(stem))},
                    {"schemaEncoding", "jsonschema"},
                    {"schema", CompactSchema(stem)}};
      };
      services.push_back({{"id", service.id},
                          {"name", service.name},
                          {"type", service.type},
                          {"request", definition(service.request_schema)},
                          {"response", definition(service.response_schema)},
                          {"requestSchema", CompactSchema(service.request_schema)},
                          {"responseSchema", CompactSchema(service.response_schema)}});
    }
    return json{{"op", "advertiseServices"}, {"services", services}}.dump();
  }();
  return message;
}

}  // namespace flagsim::gateway
