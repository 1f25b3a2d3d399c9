// The server's LCM messages as the JSON the gateway's channels carry (schemas/*.json), and
// the parameter table as Foxglove protocol parameters.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "flagsim/ack_t.hpp"
#include "flagsim/frame_t.hpp"
#include "flagsim/params_t.hpp"
#include "flagsim/state_t.hpp"
#include "flagsim/status_t.hpp"
#include "flagsim/timeline_t.hpp"

namespace flagsim::gateway {

nlohmann::json StatusJson(const status_t& status);
nlohmann::json ParamsJson(const params_t& params);
nlohmann::json TimelineJson(const timeline_t& timeline);
nlohmann::json StateSummaryJson(const state_t& state);
nlohmann::json CameraJson(const frame_t& frame);
nlohmann::json AckJson(const ack_t& ack);

/// A parameter's value as the protocol carries it: a number, a boolean, or a choice's name.
nlohmann::json ParameterValue(const parameter_t& parameter);
/// {"name", "value"} for each of `params`, in the protocol's parameterValues form.
nlohmann::json ParameterValues(const params_t& params);

/// A key's law as the JSON names it ("step", "linear", "smooth", "cubic"); "" if none.
std::string LawName(int law);
/// The LAW_* constant a name denotes; -1 if none.
int LawOfName(const std::string& name);

/// {"sec", "nsec"} of a time in microseconds since the Unix epoch.
nlohmann::json TimeJson(int64_t utime);
/// A time in microseconds since the Unix epoch in nanoseconds, as the protocol's and MCAP's
/// timestamps are; 0 for none.
uint64_t Nanoseconds(int64_t utime);

/// Whether `camera` (CameraJson) shows another pose than `*last` (the frame id aside); then
/// `*last` becomes it. The camera goes out when it moved, not with every frame.
bool CameraMoved(const nlohmann::json& camera, nlohmann::json* last);

/// `message` as text for a client. JSON is UTF-8, but a string from the bus holds whatever bytes
/// its publisher put there: bytes that are not UTF-8 become U+FFFD, where nlohmann's dump()
/// would throw (and one hostile datagram would end the gateway).
std::string JsonText(const nlohmann::json& message);

}  // namespace flagsim::gateway
