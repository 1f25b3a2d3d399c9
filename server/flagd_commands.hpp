// flagd's command line: each Add* registers one command (its options, its help) and sets the
// callback that runs it once the line is parsed, keeping its exit code in the Invocation:
//
//   flagd [options]      the live server (serve_command.cpp); runs when no subcommand is given
//   flagd render ...     a scene offline, into a log and PNG frames (render_command.cpp)
//   flagd replay LOG     a recorded session stepped again and checked (replay_command.cpp)
//
// Exit codes: 0 ok, 1 failed (a file, a difference in a replay), 2 usage.
#pragma once

#include <CLI/CLI.hpp>
#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include "messages/channels.hpp"
#include "server/scene/scene.hpp"

namespace flagsim {

enum FlagdExit { kFlagdOk = 0, kFlagdFailed = 1, kFlagdUsage = 2 };

/// Options every command takes, and the scene's: where it comes from and what overrides it.
struct FlagdGlobals {
  std::string lcm_url;
  std::string prefix = Channels::kDefaultPrefix;
  std::string log_level = "info";
  std::string scene = "breeze";          ///< a preset or a scene file (.toml)
  std::vector<std::string> assignments;  ///< --set NAME=VALUE
};

/// One run of flagd: the global options, the stop token (SIGINT / SIGTERM) and the exit code of
/// the command that ran.
struct FlagdInvocation {
  explicit FlagdInvocation(const std::atomic<bool>& stop_token) : stop(stop_token) {}

  /// `command` runs `run` once the line is parsed (the logger set up first), its exit code kept.
  void RunOnParse(CLI::App* command, std::function<int()> run);

  /// Whether an option of the live server's only (--resume) came with a subcommand; then says so.
  bool StartsAServer() const;

  FlagdGlobals globals;
  const CLI::Option* resume = nullptr;  ///< the server's --resume (AddServerCommand)
  const std::atomic<bool>& stop;
  int exit_code = kFlagdUsage;
};

/// The scene named by --scene with every --set applied and checked by the parameter table.
/// Throws SceneError naming what is wrong (a usage error).
Scene BuildScene(const FlagdGlobals& globals);

void AddServerCommand(CLI::App& app, FlagdInvocation& invocation);  ///< the main command's own options
void AddRenderCommand(CLI::App& app, FlagdInvocation& invocation);
void AddReplayCommand(CLI::App& app, FlagdInvocation& invocation);

}  // namespace flagsim
