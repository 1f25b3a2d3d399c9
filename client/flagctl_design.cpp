// flagctl design NAME: the flag's design, a built-in one by name, as the `design` parameter
// (PARAM), so that it is journaled, replayed and reset like every parameter.
#include <memory>
#include <string>

#include "client/flagctl_commands.hpp"
#include "client/flagctl_link.hpp"
#include "flagsim/param_command_t.hpp"

namespace flagsim {

void AddDesignCommand(CLI::App& app, Invocation& invocation) {
  CLI::App* design = app.add_subcommand("design", "show a built-in design on the flag (the design parameter)");
  auto name = std::make_shared<std::string>();
  design->add_option("NAME", *name, "nordic_cross, tricolour or checker (flagctl params lists them)")->required();
  invocation.RunOnParse(design, [&invocation, name] {
    param_command_t command{};
    command.names = {"design"};
    command.values = {*name};
    command.num_assignments = 1;
    return SendCommand(invocation.globals, &Channels::param, command);
  });
}

}  // namespace flagsim
