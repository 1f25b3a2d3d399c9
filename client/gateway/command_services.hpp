// The gateway's services that are one command each: a table from the service to the server's
// channel it goes out on and the parser that makes it (command_requests.hpp), in place of a
// switch. Services that are more (/flag/record, /flag/design) are the hub's own.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <variant>

#include "flagsim/camera_command_t.hpp"
#include "flagsim/design_piece_t.hpp"
#include "flagsim/keyframe_command_t.hpp"
#include "flagsim/param_command_t.hpp"
#include "flagsim/refresh_request_t.hpp"
#include "flagsim/time_command_t.hpp"
#include "flagsim/wind_command_t.hpp"
#include "messages/channels.hpp"

namespace flagsim::gateway {

/// Any command the gateway relays to a server.
using Command = std::variant<wind_command_t, param_command_t, camera_command_t, keyframe_command_t,
                             time_command_t, refresh_request_t, design_piece_t>;

struct CommandService {
  std::string Channels::*channel;  ///< where the command goes
  /// "" and the command, or why the request is not one.
  std::string (*parse)(const nlohmann::json& request, Command* command);
};

/// The entry of base service id `service` (wind, set, camera, keyframe, refresh, time); nullptr
/// for the others.
const CommandService* FindCommandService(uint32_t service);

}  // namespace flagsim::gateway
