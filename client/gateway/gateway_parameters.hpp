// The servers' parameters as the Foxglove protocol has them: one flat list of names for all the
// servers a gateway serves. On a gateway of one server they are named as the server names them
// ("stiffness"); on a gateway of several, each server's carry its path ("/ALPHA_/stiffness").
//
//   getParameters(names)  => each server's table, the names asked for, renamed
//   setParameters([{name, value}]) => one PARAM command to the one server they belong to
//   PARAMS with changed values => parameterValues, renamed, to clients following them
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "flagsim/param_command_t.hpp"
#include "flagsim/params_t.hpp"

namespace flagsim::gateway {

/// The name a client sees for the parameter `name` of the server at `path`.
std::string ParameterNameIn(const std::string& path, const std::string& name);
/// The server's own name for `name` if it names a parameter of the server at `path`; else nullopt.
std::optional<std::string> ParameterNameOf(const std::string& path, const std::string& name);

/// parameterValues' entries ([{name, value, type}]) of `params` whose client names are in
/// `names` (all if it is empty), named for clients.
nlohmann::json ParameterValuesIn(const std::string& path, const params_t& params,
                                 const nlohmann::json& names);
/// [{name, value}] with each name a client's name.
nlohmann::json RenamedValues(const std::string& path, const nlohmann::json& values);

/// setParameters' `parameters` ([{name, value}]) as one PARAM command to the server at `path`;
/// `names` gets the names as the client gave them. "" or what is wrong (a name of another server,
/// a missing value, a value no parameter takes), naming the parameter.
std::string ParamCommandOf(const nlohmann::json& parameters, const std::string& path,
                           param_command_t* command, nlohmann::json* names);

}  // namespace flagsim::gateway
