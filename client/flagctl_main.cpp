// flagctl: the thin client. Steers a flagd server (wind, set, reset, camera, keyframe, time, refresh),
// reads its streams (params, status, watch, snapshot, keyframe list), records sessions (record),
// turns logs into pictures (export) and serves the live view to browsers (serve). This file is the
// command line: the global options, one registration per subcommand (flagctl_commands.hpp), whose
// callback runs it once the line is parsed. Exit codes: 0 ok, 1 failed, 2 usage, 3 rejected by the
// server (its reason printed), 4 no answer, 5 nothing to export.
#include <CLI/CLI.hpp>
#include <atomic>
#include <csignal>
#include <cstdio>
#include <exception>

#include "client/flagctl_commands.hpp"
#include "common/cli_checks.hpp"

namespace {

std::atomic<bool> stop_requested{false};  // set by SIGINT / SIGTERM; lock-free, so signal-safe

void OnSignal(int) { stop_requested.store(true); }

/// --lcm-url, --prefix, --timeout and --key-file, taken before or after the subcommand.
void AddGlobalOptions(CLI::App& app, flagsim::Globals& globals) {
  app.fallthrough();
  app.add_option("--lcm-url", globals.lcm_url,
                 "LCM URL (default: $LCM_DEFAULT_URL, else udpm://239.255.76.67:7667?ttl=0)");
  globals.prefix_option =
      app.add_option("--prefix", globals.prefix, "channel prefix of the server: letters, digits and '_'")
          ->check(flagsim::ChannelPrefix())
          ->capture_default_str();
  app.add_option("--timeout", globals.timeout, "seconds to wait for an answer")
      ->check(flagsim::AboveZero())
      ->capture_default_str();
  app.add_option("--key-file", globals.key_file,
                 "sign every command with the first key in this file (flagctl keygen), for a server "
                 "started with --key-file; also $FLAGSIM_KEY_FILE")
      ->envname("FLAGSIM_KEY_FILE");
}

}  // namespace

int main(int argc, char** argv) {
  using namespace flagsim;
  CLI::App app{
      "flagctl: steer and watch a flagd server over LCM\n"
      "exit codes: 0 ok, 1 failed (a file, ffmpeg), 2 usage, 3 rejected by the server, 4 no answer within "
      "--timeout, 5 nothing to export"};
  app.require_subcommand(1);
  Invocation invocation(stop_requested);
  AddGlobalOptions(app, invocation.globals);
  for (const auto add : {AddWindCommand, AddSetCommand, AddResetCommand, AddParamsCommand, AddStatusCommand,
                         AddServersCommand, AddRefreshCommand, AddWatchCommand, AddRecordCommand,
                         AddExportCommand, AddSnapshotCommand, AddCameraCommand, AddKeyframeCommand,
                         AddTimeCommand, AddDesignCommand, AddServeCommand, AddKeygenCommand}) {
    add(app, invocation);
  }
  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);
  try {
    app.parse(argc, argv);  // the subcommand runs in its callback, at the end of the parse
  } catch (const CLI::ParseError& error) {
    const std::string problem = SubcommandProblem(app, error);
    if (problem.empty()) return app.exit(error) == 0 ? kOk : kUsage;
    std::fprintf(stderr, "flagctl: %s\n", problem.c_str());
    return kUsage;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "flagctl: %s\n", error.what());
    return kFailed;
  }
  return invocation.exit_code;
}
