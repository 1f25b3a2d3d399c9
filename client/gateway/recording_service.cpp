#include "client/gateway/recording_service.hpp"

namespace flagsim::gateway {

std::optional<nlohmann::json> AnswerRecordRequest(SessionRecorder& recorder, const nlohmann::json& request,
                                                  double now, std::string* problem) {
  const auto field = request.is_object() ? request.find("action") : request.end();
  const std::string action = field != request.end() && field->is_string() ? field->get<std::string>() : "";
  if (action == "start") return recorder.Start(now);
  if (action == "stop") return recorder.Stop(now);
  if (action == "status") return recorder.Status(now);
  *problem = "/flag/record: action must be start, stop or status";
  return std::nullopt;
}

}  // namespace flagsim::gateway
