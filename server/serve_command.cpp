// flagd without a subcommand: the live server. The scene (or, with --resume, a checkpoint's
// session), the keys commands must be signed with, then the server's loop until SIGINT/SIGTERM
// or its --duration, and a last line of where the flag stopped.
#include <spdlog/spdlog.h>
#include <sys/resource.h>

#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>

#include "common/cli_checks.hpp"
#include "messages/bus.hpp"
#include "messages/command_key.hpp"
#include "server/flagd_commands.hpp"
#include "server/scene/scene_file.hpp"
#include "server/service/resume_point.hpp"
#include "server/service/server.hpp"

namespace flagsim {
namespace {

struct ServerArguments {
  ServerOptions server;
  std::vector<std::string> key_files;  ///< --key-file: commands must be signed with one of their keys
  std::string resume_log;              ///< --resume LOG: start from its last checkpoint
};

/// Every key in the --key-file files. Throws std::runtime_error naming the file when one cannot
/// be read or has loose permissions, and a key name found twice.
std::vector<CommandKey> ReadKeys(const std::vector<std::string>& paths) {
  std::vector<CommandKey> keys;
  for (const std::string& path : paths) {
    for (CommandKey& key : ReadKeyFile(path)) {
      for (const CommandKey& earlier : keys)
        if (earlier.name == key.name)
          throw std::runtime_error("key file " + path + ": key '" + key.name + "' is in an earlier file too");
      keys.push_back(std::move(key));
    }
  }
  return keys;
}

/// --resume: the log's last whole checkpoint. Throws SceneError (a usage error) when there is
/// none, or when --record-inputs would write over the log it reads.
ResumePoint FindResume(const ServerArguments& arguments, const std::string& prefix) {
  std::error_code error;
  if (!arguments.server.inputs_log.empty() &&
      std::filesystem::equivalent(arguments.server.inputs_log, arguments.resume_log, error)) {
    throw SceneError("--record-inputs " + arguments.server.inputs_log + " is the log --resume reads; record into a new file");
  }
  ResumePoint point = FindResumePoint(arguments.resume_log, prefix);
  if (!point.error.empty()) throw SceneError("--resume: " + point.error);
  return point;
}

/// A resumed server's state must be its checkpoint's, bit for bit: says so, with what is lost
/// after the checkpoint, and returns true; or says how it differs and returns false.
bool ReportResume(const std::string& log, const ResumePoint& point, const Server& server) {
  const uint64_t hash = server.session().simulation().Hash();
  if (hash != point.state_hash) {
    std::fprintf(stderr, "flagd: --resume %s: the resumed state's hash %016llx is not the checkpoint's %016llx\n",
                 log.c_str(), static_cast<unsigned long long>(hash), static_cast<unsigned long long>(point.state_hash));
    return false;
  }
  std::fprintf(stderr, "flagd: resumed from %s, state hash %016llx, equal to the checkpoint's: %s\n", log.c_str(),
               static_cast<unsigned long long>(hash), DescribeResume(point).c_str());
  return true;
}

// scene or checkpoint, keys => the server's loop => where it stopped
int RunServer(const FlagdGlobals& globals, ServerArguments arguments, const std::atomic<bool>& stop) {
  Scene scene;
  std::optional<ResumePoint> resume_point;
  try {
    if (!arguments.resume_log.empty()) {
      resume_point = FindResume(arguments, globals.prefix);
      scene = resume_point->snapshot.scene;
    } else {
      scene = BuildScene(globals);
    }
    arguments.server.command_keys = ReadKeys(arguments.key_files);
  } catch (const std::exception& error) {
    std::cerr << "flagd: " << error.what() << "\n";
    return kFlagdUsage;
  }
  try {
    Bus bus(Bus::WithReceiveBuffer(globals.lcm_url, 1 << 20));
    const Channels channels(globals.prefix);
    const std::unique_ptr<Server> resumed_or_new =
        resume_point ? std::make_unique<Server>(bus, channels, resume_point->snapshot, arguments.server)
                     : std::make_unique<Server>(bus, channels, scene, arguments.server);
    Server& server = *resumed_or_new;
    if (resume_point && !ReportResume(arguments.resume_log, *resume_point, server)) return kFlagdFailed;
    spdlog::info("flagd: scene '{}' ({}x{} nodes), {} on {} with prefix {}", scene.name, scene.sim.cols, scene.sim.rows,
                 arguments.server.fast ? "as fast as possible" : "in real time", bus.url(), channels.prefix);
    spdlog::info("flagd: command authentication: {}", server.authentication());
    if (!arguments.server.inputs_log.empty()) spdlog::info("flagd: recording its inputs to {}", arguments.server.inputs_log);
    server.Run(stop);
    const auto& state = server.session().simulation().state();
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    spdlog::info("flagd: stopped at step {}, t = {:.3f} s, state hash {:016x}, peak memory {:.1f} MB", state.step,
                 state.time, server.session().simulation().Hash(), usage.ru_maxrss / 1024.0);
  } catch (const std::exception& error) {
    std::cerr << "flagd: " << error.what() << "\n";
    return kFlagdFailed;
  }
  return kFlagdOk;
}

}  // namespace

void AddServerCommand(CLI::App& app, FlagdInvocation& invocation) {
  auto arguments = std::make_shared<ServerArguments>();
  ServerArguments& a = *arguments;
  app.add_flag("--fast", a.server.fast, "step as fast as possible instead of in real time");
  app.add_option("--duration", a.server.duration,
                 "stop after this many simulated seconds, counted from where it starts (0: run until stopped)")
      ->check(ZeroOrMore());
  app.add_option("--record-inputs", a.server.inputs_log,
                 "also write what a replay needs (each applied command, the checkpoints) into this LCM "
                 "log, for `flagd replay` and `flagd --resume`");
  CLI::Option* resume =
      app.add_option("--resume", a.resume_log,
                     "start again from the last checkpoint in this log (a --record-inputs log of a server "
                     "that was killed or stopped), with the scene as it stood there; says how much came "
                     "after the checkpoint and is lost")
          ->check(CLI::ExistingFile);
  app.add_option("--key-file", a.key_files,
                 "take only commands signed with a key in this file (flagctl keygen -o FILE makes one; "
                 "readable by its owner only); repeatable. Without it, anyone on the bus may steer the server")
      ->check(CLI::ExistingFile);
  // A resumed session's scene is the checkpoint's; it is changed afterwards as any session is.
  resume->excludes(app.get_option("--scene"))->excludes(app.get_option("--set"));
  invocation.resume = resume;
  // The live server runs when no subcommand was given.
  invocation.RunOnParse(&app, [&app, &invocation, arguments]() {
    if (!app.get_subcommands().empty()) return invocation.exit_code;  // the subcommand's
    return RunServer(invocation.globals, *arguments, invocation.stop);
  });
}

}  // namespace flagsim
