// Checks of the command line that speak as the user typed: number ranges that name their bound
// ("above 0", not CLI11's own, which prints the largest double in full), and an unknown
// subcommand named as such (CLI11 says only that a subcommand is required). Header-only, for
// flagctl and flagd alike.
#pragma once

#include <CLI/CLI.hpp>
#include <cmath>
#include <string>
#include <vector>

namespace flagsim {

/// A finite number above 0. Shown in help as POSITIVE, as CLI11's own.
inline CLI::Validator AboveZero() {
  return CLI::Validator(
      [](std::string& input) -> std::string {
        double value = 0;
        if (!CLI::detail::lexical_cast(input, value)) return "'" + input + "' is not a number";
        return std::isfinite(value) && value > 0 ? "" : input + " is out of range; allowed above 0";
      },
      "POSITIVE");
}

/// A finite number, 0 or above. Shown in help as NONNEGATIVE, as CLI11's own.
inline CLI::Validator ZeroOrMore() {
  return CLI::Validator(
      [](std::string& input) -> std::string {
        double value = 0;
        if (!CLI::detail::lexical_cast(input, value)) return "'" + input + "' is not a number";
        return std::isfinite(value) && value >= 0 ? "" : input + " is out of range; allowed 0 or more";
      },
      "NONNEGATIVE");
}

/// After a failed parse: "'WORD' is not a subcommand[ of NAME]; allowed: ..." when the deepest
/// subcommand given wants one and WORD was left over, else "".
inline std::string UnknownSubcommand(CLI::App& app) {
  CLI::App* deepest = &app;
  while (!deepest->get_subcommands().empty()) deepest = deepest->get_subcommands().front();
  const std::vector<std::string> left = app.remaining(true);
  if (deepest->get_require_subcommand_min() == 0 || left.empty() || left.front().rfind("-", 0) == 0) {
    return "";
  }
  std::string names;
  for (const CLI::App* command : deepest->get_subcommands([](const CLI::App*) { return true; })) {
    names += (names.empty() ? "" : ", ") + command->get_name();
  }
  const std::string of = deepest == &app ? "" : " of " + deepest->get_name();
  return "'" + left.front() + "' is not a subcommand" + of + "; allowed: " + names;
}

}  // namespace flagsim
