// flagctl design NAME: the flag's design, a built-in one by name, as the `design` parameter
// (PARAM), so that it is journaled, replayed and reset like every parameter.
#include <memory>
#include <string>

#include "client/flagctl_commands.hpp"

namespace flagsim {

void AddDesignCommand(CLI::App& app, Invocation& invocation) {
  CLI::App* design = app.add_subcommand("design", "show a built-in design on the flag (the design parameter)");
  auto name = std::make_shared<std::string>();
  design->add_option("NAME", *name, "nordic_cross, tricolour or checker (flagctl params lists them)")->required();
  invocation.RunOnParse(design, [&invocation, name] { return SendParams(invocation.globals, {"design=" + *name}, false); });
}

}  // namespace flagsim
