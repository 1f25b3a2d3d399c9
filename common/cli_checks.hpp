// Checks of the command line that speak as the user typed: number ranges that name their bound
// ("above 0", not CLI11's own, which prints the largest double in full), a channel prefix that
// makes channel names, and an unknown or missing subcommand named as such, with the allowed ones
// (CLI11 says only that one is required). Header-only, for flagctl and flagd alike.
#pragma once

#include <CLI/CLI.hpp>
#include <cmath>
#include <string>
#include <vector>

#include "messages/channels.hpp"

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

/// A channel prefix: letters, digits and '_' (Channels::CheckPrefix). Shown in help as PREFIX.
inline CLI::Validator ChannelPrefix() {
  return CLI::Validator([](std::string& input) { return Channels::CheckPrefix(input); }, "PREFIX");
}

/// A server's channel prefix: as ChannelPrefix, or auto for a random one of its own
/// (Channels::RandomPrefix), put in its place.
inline CLI::Validator ServerPrefix() {
  return CLI::Validator(
      [](std::string& input) {
        if (input == "auto") input = Channels::RandomPrefix();
        const std::string problem = Channels::CheckPrefix(input);
        return problem.empty() ? problem : problem + ", or auto";
      },
      "PREFIX|auto");
}

/// After a parse that failed with `error`, when it failed because the deepest subcommand given
/// wants one of its own: "'WORD' is not a subcommand[ of NAME]; allowed: ..." for a WORD left
/// over, "NAME needs a subcommand; allowed: ..." for none; else "" (CLI11's own message says
/// what is wrong).
inline std::string SubcommandProblem(CLI::App& app, const CLI::ParseError& error) {
  if (dynamic_cast<const CLI::RequiredError*>(&error) == nullptr &&
      dynamic_cast<const CLI::ExtrasError*>(&error) == nullptr) {
    return "";
  }
  CLI::App* deepest = &app;
  while (!deepest->get_subcommands().empty()) deepest = deepest->get_subcommands().front();
  if (deepest->get_require_subcommand_min() == 0) return "";
  const std::vector<std::string> left = app.remaining(true);
  if (!left.empty() && left.front().rfind("-", 0) == 0) return "";  // an unknown option
  std::string names;
  for (const CLI::App* command : deepest->get_subcommands([](const CLI::App*) { return true; })) {
    names += (names.empty() ? "" : ", ") + command->get_name();
  }
  const std::string name = deepest == &app ? "" : deepest->get_name();
  if (left.empty())
    return (name.empty() ? "a subcommand is required" : name + " needs a subcommand") + "; allowed: " + names;
  return "'" + left.front() + "' is not a subcommand" + (name.empty() ? "" : " of " + name) +
         "; allowed: " + names;
}

}  // namespace flagsim
