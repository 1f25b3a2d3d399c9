#include "client/gateway/gateway_parameters.hpp"

#include <algorithm>

#include "client/gateway/bus_json.hpp"
#include "client/gateway/command_requests.hpp"
#include "common/printable_text.hpp"

namespace flagsim::gateway {

using nlohmann::json;

std::string ParameterNameIn(const std::string& path, const std::string& name) {
  return path.empty() ? name : path + "/" + name;
}

std::optional<std::string> ParameterNameOf(const std::string& path, const std::string& name) {
  if (path.empty()) return name;
  if (name.size() <= path.size() + 1 || name.compare(0, path.size(), path) != 0 || name[path.size()] != '/')
    return std::nullopt;
  return name.substr(path.size() + 1);
}

json ParameterValuesIn(const std::string& path, const params_t& params, const json& names) {
  json values = json::array();
  for (json value : ParameterValues(params)) {
    value["name"] = ParameterNameIn(path, value["name"].get<std::string>());
    const bool wanted = names.empty() || std::find(names.begin(), names.end(), value["name"]) != names.end();
    if (wanted) values.push_back(std::move(value));
  }
  return values;
}

json RenamedValues(const std::string& path, const json& values) {
  json renamed = values;
  for (json& value : renamed) value["name"] = ParameterNameIn(path, value["name"].get<std::string>());
  return renamed;
}

std::string ParamCommandOf(const json& parameters, const std::string& path, param_command_t* command,
                           json* names) {
  *names = json::array();
  for (const json& parameter : parameters) {
    const auto name = parameter.is_object() ? parameter.find("name") : parameter.end();
    if (!parameter.is_object() || name == parameter.end() || !name->is_string())
      return "setParameters: each parameter needs a name";
    const std::string& client_name = name->get_ref<const std::string&>();
    const std::optional<std::string> own = ParameterNameOf(path, client_name);
    if (!own) {
      return "setParameters: '" + PrintableText(client_name) + "' is not a parameter of " + path +
             "; set each server's parameters in a message of their own";
    }
    const auto value = parameter.find("value");
    if (value == parameter.end()) return client_name + ": parameters cannot be unset; give a value";
    std::string problem;
    const std::string text = ParameterText(*own, *value, &problem);
    if (!problem.empty()) return problem;
    command->names.push_back(*own);
    command->values.push_back(text);
    names->push_back(client_name);
  }
  command->num_assignments = static_cast<int32_t>(command->names.size());
  return command->num_assignments == 0 ? "setParameters: no parameters given" : "";
}

}  // namespace flagsim::gateway
