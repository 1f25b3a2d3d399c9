#include "client/gateway/gateway_catalog.hpp"

#include <map>
#include <stdexcept>

namespace flagsim::gateway {

// Generated from schemas/ by cmake/embed_text.cmake.
const std::vector<std::pair<std::string_view, std::string_view>>& GatewaySchemas();

namespace {
using nlohmann::json;

/// A schema as sent: JSON ones without their layout's whitespace, text ones as written; each
/// made once (every client of every server is sent them).
const std::string& CompactSchema(std::string_view stem) {
  static std::map<std::string_view, std::string> compact;
  const auto found = compact.find(stem);
  if (found != compact.end()) return found->second;
  const json parsed = json::parse(Schema(stem), nullptr, false);
  return compact[stem] = parsed.is_discarded() ? std::string(Schema(stem)) : parsed.dump();
}

json ChannelJson(const ChannelInfo& channel, uint32_t id, const std::string& path) {
  return {{"id", id},
          {"topic", path + std::string(channel.topic)},
          {"encoding", channel.encoding},
          {"schemaName", channel.schema_name},
          {"schemaEncoding", channel.schema_encoding},
          {"schema", CompactSchema(channel.schema_file)}};
}

json ServiceJson(const ServiceInfo& service, uint32_t id, const std::string& path) {
  const auto definition = [](std::string_view stem) {
    return json{{"encoding", "json"},
                {"schemaName", json::parse(Schema(stem)).value("title", std::string(stem))},
                {"schemaEncoding", "jsonschema"},
                {"schema", CompactSchema(stem)}};
  };
  return {{"id", id},
          {"name", path + std::string(service.name)},
          {"type", service.type},
          {"request", definition(service.request_schema)},
          {"response", definition(service.response_schema)},
          {"requestSchema", CompactSchema(service.request_schema)},
          {"responseSchema", CompactSchema(service.response_schema)}};
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
      {kServersChannel, "/gateway/servers", "json", "flagsim.Servers", "jsonschema", "servers"},
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

const ChannelInfo* FindChannel(uint32_t base) {
  return base >= 1 && base <= AdvertisedChannels().size() ? &AdvertisedChannels()[base - 1] : nullptr;
}

const ServiceInfo* FindService(uint32_t base) {
  return base >= 1 && base <= AdvertisedServices().size() ? &AdvertisedServices()[base - 1] : nullptr;
}

std::string_view Schema(std::string_view stem) {
  for (const auto& [name, text] : GatewaySchemas()) {
    if (name == stem) return text;
  }
  throw std::out_of_range("no schema " + std::string(stem));
}

json ServerChannelsJson(uint32_t slot, const std::string& path) {
  json channels = json::array();
  for (uint32_t base = 1; base <= kServerChannelCount; ++base)
    channels.push_back(ChannelJson(*FindChannel(base), IdIn(slot, base), path));
  return channels;
}

json ServerServicesJson(uint32_t slot, const std::string& path) {
  json services = json::array();
  for (const ServiceInfo& service : AdvertisedServices())
    services.push_back(ServiceJson(service, IdIn(slot, service.id), path));
  return services;
}

json GatewayChannelsJson() {
  return json::array({ChannelJson(*FindChannel(kGatewayStatusChannel), kGatewayStatusChannel, ""),
                      ChannelJson(*FindChannel(kServersChannel), kServersChannel, "")});
}

std::vector<uint32_t> ServerChannelIds(uint32_t slot) {
  std::vector<uint32_t> ids;
  for (uint32_t base = 1; base <= kServerChannelCount; ++base) ids.push_back(IdIn(slot, base));
  return ids;
}

std::vector<uint32_t> ServerServiceIds(uint32_t slot) {
  std::vector<uint32_t> ids;
  for (uint32_t base = 1; base <= kServiceCount; ++base) ids.push_back(IdIn(slot, base));
  return ids;
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

}  // namespace flagsim::gateway
