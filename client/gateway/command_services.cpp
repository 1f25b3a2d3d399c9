#include "client/gateway/command_services.hpp"

#include <map>

#include "client/gateway/command_requests.hpp"
#include "client/gateway/gateway_catalog.hpp"

namespace flagsim::gateway {
namespace {

/// A parser of one command type as one of the table's.
template <class Message, std::string (*kParse)(const nlohmann::json&, Message*)>
std::string ParseInto(const nlohmann::json& request, Command* command) {
  Message message{};
  const std::string problem = kParse(request, &message);
  if (problem.empty()) *command = message;
  return problem;
}

std::string RefreshOf(const nlohmann::json&, Command* command) {
  *command = refresh_request_t{};
  return "";
}

}  // namespace

const CommandService* FindCommandService(uint32_t service) {
  static const std::map<uint32_t, CommandService> services = {
      {kWindService, {&Channels::wind, ParseInto<wind_command_t, WindCommandOf>}},
      {kSetService, {&Channels::param, ParseInto<param_command_t, SetCommandOf>}},
      {kCameraService, {&Channels::camera, ParseInto<camera_command_t, CameraCommandOf>}},
      {kKeyframeService, {&Channels::keyframe, ParseInto<keyframe_command_t, KeyframeCommandOf>}},
      {kTimeService, {&Channels::time, ParseInto<time_command_t, TimeCommandOf>}},
      {kRefreshService, {&Channels::refresh, RefreshOf}},
  };
  const auto found = services.find(service);
  return found == services.end() ? nullptr : &found->second;
}

}  // namespace flagsim::gateway
