// The fixture of the command-side tests: a server and flagctl's command client on one in-process
// bus (memq://), the server stepping on a simulated clock while the client waits for answers.
#pragma once

#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "client/command_client.hpp"
#include "server/scene/parameter_table.hpp"
#include "server/service/server.hpp"
#include "tests/service/fixed_model.hpp"
#include "tests/service/simulated_clock.hpp"

namespace flagsim {

class CommandIntakeTest : public ::testing::Test {
 protected:
  // The server steps one step of the simulated clock each time the client looks for its answer:
  // accepted WIND and PARAM commands are answered once the flag has taken
  // CommandIntake::kSettleSteps steps under them.
  CommandIntakeTest()
      : bus_("memq://"),
        server_(bus_, channels_, testing::FixedModel(Scene{}), clock_.ServerOnIt()),
        client_(bus_, channels_, 5.0, {}, clock_.Reader()) {
    client_.WhileWaiting([this] { clock_.Step(server_); });
  }

  const Scene& scene() const { return server_.session().scene(); }
  const ServerStats& stats() const { return server_.stats(); }

  CommandOutcome SetParams(std::vector<std::string> names, std::vector<std::string> values) {
    param_command_t command{};
    command.names = std::move(names);
    command.values = std::move(values);
    command.num_assignments = static_cast<int32_t>(command.names.size());
    return client_.Send(channels_.param, command);
  }

  /// Every parameter's current value, to check that a rejection changed nothing.
  std::vector<double> Values() const {
    std::vector<double> values;
    for (const Parameter& parameter : ParameterTable::Get().parameters())
      values.push_back(parameter.get(scene()));
    return values;
  }

  testing::SimulatedClock clock_;
  Bus bus_;
  Channels channels_;
  Server server_;
  CommandClient client_;
};

}  // namespace flagsim
