// A client's JSON request (a service call or a client-published message, schemas/*_request.json)
// turned into the LCM command flagd takes. Only the JSON's shape is checked here: a missing or
// mistyped field is refused with its name and what is expected; values out of range go to the
// server, whose ACK names the field and the allowed range. Angles arrive in degrees (as people
// and flagctl give them) and leave in the message's radians.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "flagsim/camera_command_t.hpp"
#include "flagsim/keyframe_command_t.hpp"
#include "flagsim/param_command_t.hpp"
#include "flagsim/time_command_t.hpp"
#include "flagsim/wind_command_t.hpp"

namespace flagsim::gateway {

/// Each returns "" and fills `command`, or the reason the request is not one.
std::string WindCommandOf(const nlohmann::json& request, wind_command_t* command);
std::string SetCommandOf(const nlohmann::json& request, param_command_t* command);
std::string CameraCommandOf(const nlohmann::json& request, camera_command_t* command);
std::string KeyframeCommandOf(const nlohmann::json& request, keyframe_command_t* command);
std::string TimeCommandOf(const nlohmann::json& request, time_command_t* command);

/// A parameter value from JSON as PARAM's text ("1500", "true", "rk4"); "" with *error set
/// for what cannot be one (null, arrays, objects).
std::string ParameterText(const std::string& name, const nlohmann::json& value, std::string* error);

}  // namespace flagsim::gateway
