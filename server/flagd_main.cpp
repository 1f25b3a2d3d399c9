// flagd: the flag simulation server. Steps the flag in real time (or as fast as it can), draws
// and streams its frames as tiles, publishes STATE, PARAMS and STATUS, and takes WIND, PARAM,
// CAMERA, KEYFRAME, TIME and REFRESH commands over LCM (serve_command.cpp); `flagd render` runs a
// scene offline (render_command.cpp); `flagd replay` steps a recorded session again and checks it
// (replay_command.cpp). This file is the command line: the global options and one registration
// per command (flagd_commands.hpp), whose callback runs it once the line is parsed.
#include <CLI/CLI.hpp>
#include <atomic>
#include <csignal>
#include <cstdio>

#include "common/cli_checks.hpp"
#include "server/flagd_commands.hpp"

namespace {

std::atomic<bool> stop_requested{false};  // set by SIGINT / SIGTERM; lock-free, so signal-safe

void OnSignal(int) { stop_requested.store(true); }

/// --lcm-url, --prefix, --log-level, --scene and --set, taken before or after a subcommand.
void AddGlobalOptions(CLI::App& app, flagsim::FlagdGlobals& globals) {
  app.fallthrough();
  app.add_option("--lcm-url", globals.lcm_url,
                 "LCM URL (default: $LCM_DEFAULT_URL, else udpm://239.255.76.67:7667?ttl=0)");
  app.add_option("--prefix", globals.prefix,
                 "channel prefix, so several servers share a bus: letters, digits and '_'; auto: "
                 "FLAGSIM_ and six random hex digits (replicas started alike), said as it starts")
      ->transform(flagsim::ServerPrefix())
      ->capture_default_str();
  app.add_option("--log-level", globals.log_level, "trace, debug, info, warn, error or off")
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error", "off"}))
      ->capture_default_str();
  app.add_option("--scene", globals.scene, "a preset (breeze, calm, gale, hanging) or a scene file (.toml)")
      ->capture_default_str();
  app.add_option("--set", globals.assignments, "override a parameter: NAME=VALUE (repeatable)");
}

}  // namespace

int main(int argc, char** argv) {
  using namespace flagsim;
  CLI::App app{"flagd: a flag on a pole in the wind, simulated, steered and streamed over LCM"};
  FlagdInvocation invocation(stop_requested);
  AddGlobalOptions(app, invocation.globals);
  for (const auto add : {AddServerCommand, AddRenderCommand, AddReplayCommand}) add(app, invocation);
  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);
  try {
    app.parse(argc, argv);  // the command runs in its callback, at the end of the parse
  } catch (const CLI::ParseError& error) {
    return app.exit(error) == 0 ? kFlagdOk : kFlagdUsage;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "flagd: %s\n", error.what());
    return kFlagdFailed;
  }
  return invocation.exit_code;
}
