// The subcommands that steer a server (wind, set, reset, refresh) and read its tables (params,
// status): each a registration that sets the callback running it.
#include "client/flagctl_commands.hpp"

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "client/flagctl_link.hpp"
#include "client/printing.hpp"
#include "flagsim/param_command_t.hpp"
#include "flagsim/params_t.hpp"
#include "flagsim/refresh_request_t.hpp"
#include "flagsim/state_t.hpp"
#include "flagsim/status_t.hpp"
#include "flagsim/wind_command_t.hpp"

namespace flagsim {

int SendParams(const Globals& globals, const std::vector<std::string>& assignments, bool reset) {
  param_command_t command{};
  command.reset_to_scene = reset;
  for (const std::string& assignment : assignments) {
    const size_t equals = assignment.find('=');
    if (equals == std::string::npos || equals == 0) {
      std::fprintf(stderr, "flagctl: '%s' is not NAME=VALUE\n", assignment.c_str());
      return kUsage;
    }
    const std::string name = assignment.substr(0, equals), value = assignment.substr(equals + 1);
    const auto same = std::find(command.names.begin(), command.names.end(), name);
    if (same != command.names.end()) {
      std::fprintf(stderr, "flagctl: %s is set twice (%s=%s, %s); give each parameter once\n", name.c_str(),
                   name.c_str(), command.values[same - command.names.begin()].c_str(), assignment.c_str());
      return kUsage;
    }
    command.names.push_back(name);
    command.values.push_back(value);
  }
  command.num_assignments = static_cast<int32_t>(command.names.size());
  return SendCommand(globals, &Channels::param, command);
}

namespace {

/// REFRESH => ACK => the full state published for it, in a line.
int Refresh(const Globals& globals) {
  Link link(globals);
  CommandClient client(link.bus, link.channels, globals.timeout, link.signer);
  std::optional<state_t> state;
  SubscribeDecoded<state_t>(link.bus, link.channels.state, [&state](const state_t& s) { state = s; });
  const CommandOutcome outcome = client.Send(link.channels.refresh, refresh_request_t{});
  if (outcome.result != CommandOutcome::kAccepted) return Report(link, outcome);
  state.reset();  // the full state published for this request comes after the ACK
  if (!HandleUntil(link.bus, globals.timeout, [&state] { return state.has_value(); })) {
    return link.NoAnswer("STATE");
  }
  std::printf("step %lld  t = %.3f s  %d x %d nodes  state hash %016llx\n",
              static_cast<long long>(state->step), state->sim_time, state->cols, state->rows,
              static_cast<unsigned long long>(state->state_hash));
  return kOk;
}

}  // namespace

void AddWindCommand(CLI::App& app, Invocation& invocation) {
  CLI::App* wind =
      app.add_subcommand("wind", "set the wind velocity (m/s, world frame: x along the flag, y up)");
  auto command = std::make_shared<wind_command_t>();
  auto velocity = std::make_shared<std::vector<double>>();
  wind->add_option("velocity", *velocity, "VX VY VZ in m/s")->expected(3)->required();
  wind->add_option("--gust", command->gust, "gust strength, fraction of the wind speed (0 .. 1)")
      ->capture_default_str();
  wind->add_option("--ramp", command->ramp_time, "seconds of simulated time to reach this wind (0 .. 60)")
      ->capture_default_str();
  invocation.RunOnParse(wind, [&invocation, command, velocity] {
    for (int k = 0; k < 3; ++k) command->velocity[k] = (*velocity)[k];
    return SendCommand(invocation.globals, &Channels::wind, *command);
  });
}

void AddSetCommand(CLI::App& app, Invocation& invocation) {
  CLI::App* set = app.add_subcommand("set", "set parameters: NAME=VALUE ... (see flagctl params)");
  auto assignments = std::make_shared<std::vector<std::string>>();
  set->add_option("assignments", *assignments, "NAME=VALUE pairs, applied together or not at all")
      ->required();
  invocation.RunOnParse(
      set, [&invocation, assignments] { return SendParams(invocation.globals, *assignments, false); });
}

void AddResetCommand(CLI::App& app, Invocation& invocation) {
  CLI::App* reset = app.add_subcommand(
      "reset",
      "restore the scene's parameters, wind and timeline, flag at rest; the camera stays (camera reset)");
  auto assignments = std::make_shared<std::vector<std::string>>();
  reset->add_option("assignments", *assignments, "NAME=VALUE pairs to apply after the reset");
  invocation.RunOnParse(
      reset, [&invocation, assignments] { return SendParams(invocation.globals, *assignments, true); });
}

void AddParamsCommand(CLI::App& app, Invocation& invocation) {
  CLI::App* params = app.add_subcommand("params", "print the parameter table with current values");
  invocation.RunOnParse(params, [&invocation] {
    return AwaitAndPrint<params_t>(invocation.globals, &Channels::params, "PARAMS",
                                   [](const params_t& message) { PrintParams(message, std::cout); });
  });
}

void AddStatusCommand(CLI::App& app, Invocation& invocation) {
  CLI::App* status = app.add_subcommand("status", "print the server's health");
  invocation.RunOnParse(status, [&invocation] {
    return AwaitAndPrint<status_t>(invocation.globals, &Channels::status, "STATUS",
                                   [](const status_t& message) { PrintStatus(message, std::cout); });
  });
}

void AddRefreshCommand(CLI::App& app, Invocation& invocation) {
  CLI::App* refresh = app.add_subcommand("refresh", "request a full state (and frame) now");
  invocation.RunOnParse(refresh, [&invocation] { return Refresh(invocation.globals); });
}

}  // namespace flagsim
