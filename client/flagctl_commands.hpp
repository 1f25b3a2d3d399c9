// flagctl's subcommands: each Add*Command registers one on the command line (its options, its
// help) and sets the callback that runs it once the line is parsed, keeping its exit code in the
// Invocation: 0 ok, 1 failed (a file, ffmpeg), 2 usage, 3 rejected by the server (its reason
// printed), 4 no answer within the timeout, 5 nothing to export.
#pragma once

#include <CLI/CLI.hpp>
#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include "messages/channels.hpp"
#include "messages/command_mac.hpp"

namespace flagsim {

enum ExitCode { kOk = 0, kFailed = 1, kUsage = 2, kRejected = 3, kNoAnswer = 4, kNothingToExport = 5 };

/// Options every subcommand takes.
struct Globals {
  std::string lcm_url;
  std::string prefix = Channels::kDefaultPrefix;
  const CLI::Option* prefix_option = nullptr;  ///< whether --prefix was given (serve: one server, else all)
  double timeout = 2.0;                        ///< s to wait for an answer
  std::string key_file;  ///< --key-file: sign every command with its first key; "" unsigned
};

/// One run of flagctl: the global options, the stop token (set by SIGINT / SIGTERM: watch,
/// record and export stop and report) and the exit code of the subcommand that ran.
struct Invocation {
  explicit Invocation(const std::atomic<bool>& stop_token) : stop(stop_token) {}

  /// `command` runs `run` once the command line is parsed, its exit code kept in exit_code.
  void RunOnParse(CLI::App* command, std::function<int()> run) {
    command->callback([this, run = std::move(run)] { exit_code = run(); });
  }

  Globals globals;
  const std::atomic<bool>& stop;
  int exit_code = kUsage;  ///< no subcommand ran: a usage error
};

// The round trips with the server (flagctl_commands.cpp).
void AddWindCommand(CLI::App& app, Invocation& invocation);
void AddSetCommand(CLI::App& app, Invocation& invocation);
void AddResetCommand(CLI::App& app, Invocation& invocation);
void AddParamsCommand(CLI::App& app, Invocation& invocation);
void AddStatusCommand(CLI::App& app, Invocation& invocation);
void AddServersCommand(CLI::App& app, Invocation& invocation);
void AddRefreshCommand(CLI::App& app, Invocation& invocation);
// The streams (flagctl_streams.cpp).
void AddWatchCommand(CLI::App& app, Invocation& invocation);
void AddRecordCommand(CLI::App& app, Invocation& invocation);
void AddSnapshotCommand(CLI::App& app, Invocation& invocation);
// The camera's moves (flagctl_camera.cpp), the timeline (flagctl_keyframe.cpp).
void AddCameraCommand(CLI::App& app, Invocation& invocation);
void AddKeyframeCommand(CLI::App& app, Invocation& invocation);
/// "NAME=VALUE" assignments, each name once => one PARAM command, applied together or not at
/// all; `reset` first restores the scene (not the camera). Exit code.
int SendParams(const Globals& globals, const std::vector<std::string>& assignments, bool reset);

// The simulation's clock: pause, resume, step, scale (flagctl_time.cpp).
void AddTimeCommand(CLI::App& app, Invocation& invocation);
// The flag's design (flagctl_design.cpp).
void AddDesignCommand(CLI::App& app, Invocation& invocation);
// A log's frames into pictures (flagctl_export.cpp); the live view (flagctl_serve.cpp).
void AddExportCommand(CLI::App& app, Invocation& invocation);
/// flagctl export of the log at `log` to `output` (its kind by its name), as the command runs it:
/// "" or what went wrong. For the gateway, which makes a video of each recording.
std::string ExportLogTo(const Globals& globals, const std::string& log, const std::string& output,
                        const std::atomic<bool>& stop);
void AddServeCommand(CLI::App& app, Invocation& invocation);
// A new key file for signed commands (flagctl_keygen.cpp).
void AddKeygenCommand(CLI::App& app, Invocation& invocation);

}  // namespace flagsim
