// /flag/record: a server's recording started, stopped or asked about by any client, each
// answered with the recording's state (schemas/record_result.json).
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "client/gateway/session_recorder.hpp"

namespace flagsim::gateway {

/// The answer to `request` ({"action": "start" | "stop" | "status"}) at `now`; nullopt with
/// *problem set if the request is none of them.
std::optional<nlohmann::json> AnswerRecordRequest(SessionRecorder& recorder, const nlohmann::json& request,
                                                  double now, std::string* problem);

}  // namespace flagsim::gateway
