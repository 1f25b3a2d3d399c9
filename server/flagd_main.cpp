// flagd: the flag simulation server. Steps the flag in real time (or as fast as it can), draws
// and streams its frames as tiles, publishes STATE, PARAMS and STATUS, and takes WIND, PARAM,
// CAMERA, KEYFRAME and REFRESH commands over LCM, journaling what replay needs (APPLIED,
// CHECKPOINT), with --record-inputs into a log of its own too; --resume starts a session again
// from such a log's last checkpoint (resume_point.hpp). `flagd render` runs a scene offline
// instead, into an LCM log and PNG frames (render_command.hpp); `flagd replay` steps a recorded
// session again and checks it (replay_command.hpp).
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>
#include <sys/resource.h>

#include <CLI/CLI.hpp>
#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>

#include "client/cli_checks.hpp"
#include "messages/bus.hpp"
#include "messages/channels.hpp"
#include "messages/command_key.hpp"
#include "server/parallel/worker_pool.hpp"
#include "server/render_command.hpp"
#include "server/replay_command.hpp"
#include "server/scene/parameter_table.hpp"
#include "server/scene/scene_file.hpp"
#include "server/service/resume_point.hpp"
#include "server/service/server.hpp"

namespace {

std::atomic<bool> g_stop{false};  // set by SIGINT / SIGTERM; lock-free, so signal-safe

void OnSignal(int) { g_stop.store(true); }

struct Options {
  std::string lcm_url;
  std::string prefix = flagsim::Channels::kDefaultPrefix;
  std::string scene = "breeze";
  std::vector<std::string> assignments;
  flagsim::ServerOptions server;
  std::string log_level = "info";
  flagsim::RenderRequest render;
  std::string replay_log;  ///< flagd replay LOG
  flagsim::ReplayOptions replay;
  double render_fps = std::nan("");    ///< Hz; NaN: the scene's frame_rate
  int render_threads = 0;              ///< 0: the scene's threads
  std::vector<std::string> key_files;  ///< --key-file: commands must be signed with one of their keys
  std::string resume_log;              ///< --resume LOG: start from its last checkpoint
};

/// Every key in the --key-file files. Throws std::runtime_error naming the file when one cannot
/// be read or has loose permissions, and a key name found twice.
std::vector<flagsim::CommandKey> ReadKeys(const std::vector<std::string>& paths) {
  std::vector<flagsim::CommandKey> keys;
  for (const std::string& path : paths) {
    for (flagsim::CommandKey& key : flagsim::ReadKeyFile(path)) {
      for (const flagsim::CommandKey& earlier : keys)
        if (earlier.name == key.name)
          throw std::runtime_error("key file " + path + ": key '" + key.name + "' is in an earlier file too");
      keys.push_back(std::move(key));
    }
  }
  return keys;
}

/// The scene with --set overrides, each checked by the parameter table. Throws SceneError.
flagsim::Scene BuildScene(const Options& options) {
  flagsim::Scene scene = flagsim::LoadScene(options.scene);
  for (const std::string& assignment : options.assignments) {
    const size_t equals = assignment.find('=');
    if (equals == std::string::npos) {
      throw flagsim::SceneError("--set " + assignment + ": expected NAME=VALUE");
    }
    const std::string problem = flagsim::ParameterTable::Get().Assign(assignment.substr(0, equals),
                                                                      assignment.substr(equals + 1), &scene);
    if (!problem.empty()) throw flagsim::SceneError("--set " + problem);
  }
  flagsim::ParameterTable::SettleAutoModel(&scene);
  const std::string problem = flagsim::ParameterTable::CheckConsistency(scene);
  if (!problem.empty()) throw flagsim::SceneError(problem);
  return scene;
}

/// --resume: the log's last whole checkpoint. Throws SceneError (a usage error) when there is
/// none, or when --record-inputs would write over the log it reads.
flagsim::ResumePoint FindResume(const Options& options) {
  std::error_code error;
  if (!options.server.inputs_log.empty() &&
      std::filesystem::equivalent(options.server.inputs_log, options.resume_log, error)) {
    throw flagsim::SceneError("--record-inputs " + options.server.inputs_log +
                              " is the log --resume reads; record into a new file");
  }
  flagsim::ResumePoint point = flagsim::FindResumePoint(options.resume_log, options.prefix);
  if (!point.error.empty()) throw flagsim::SceneError("--resume: " + point.error);
  return point;
}

/// A resumed server's state must be its checkpoint's, bit for bit: says so, with what is lost
/// after the checkpoint, and returns true; or says how it differs and returns false.
bool ReportResume(const Options& options, const flagsim::ResumePoint& point, const flagsim::Server& server) {
  const uint64_t hash = server.session().simulation().Hash();
  if (hash != point.state_hash) {
    std::fprintf(stderr,
                 "flagd: --resume %s: the resumed state's hash %016llx is not the checkpoint's %016llx\n",
                 options.resume_log.c_str(), static_cast<unsigned long long>(hash),
                 static_cast<unsigned long long>(point.state_hash));
    return false;
  }
  std::fprintf(stderr, "flagd: resumed from %s, state hash %016llx, equal to the checkpoint's: %s\n",
               options.resume_log.c_str(), static_cast<unsigned long long>(hash),
               flagsim::DescribeResume(point).c_str());
  return true;
}

/// `flagd render`: its own copy of the scene options, so that they read naturally after it.
CLI::App* AddRenderCommand(CLI::App& app, Options& options) {
  CLI::App* render = app.add_subcommand(
      "render",
      "run a scene as fast as possible with no network, into an LCM log (the channels a live server "
      "publishes, stamped in simulated time: lcm-logplayer plays it in real time) and/or PNG frames");
  render
      ->add_option("--scene", options.scene, "a preset (breeze, calm, gale, hanging) or a scene file (.toml)")
      ->capture_default_str();
  render->add_option("--set", options.assignments, "override a parameter: NAME=VALUE (repeatable)");
  render->add_option("--duration", options.render.duration, "seconds of simulated time to render")
      ->required()
      ->check(flagsim::AboveZero());
  render->add_option("--fps", options.render_fps,
                     "frames per second of simulated time, above 0 (default: the scene's frame_rate, 30)");
  render->add_option("-o,--output", options.render.log_path, "the LCM log to write");
  render->add_option("--png-dir", options.render.png_dir, "also write each frame there as frame_%06d.png");
  render->add_option("--threads", options.render_threads, "worker threads (default: the scene's threads)")
      ->check(flagsim::AboveZero());
  render->add_option("--prefix", options.prefix, "channel prefix in the log")->capture_default_str();
  return render;
}

/// --fps and --threads are parameters, checked by the table after the --set ones. Throws
/// SceneError naming the option.
void ApplyRenderOverrides(const Options& options, flagsim::Scene* scene) {
  const auto assign = [scene](const char* option, const char* name, double value) {
    char text[32];
    std::snprintf(text, sizeof(text), "%.17g", value);
    const std::string problem = flagsim::ParameterTable::Get().Assign(name, text, scene);
    if (!problem.empty()) throw flagsim::SceneError(std::string(option) + " " + problem);
  };
  if (!std::isnan(options.render_fps)) {
    // frame_rate 0 is a live server's "no frames"; a render's frames are what it is for.
    const flagsim::Parameter& rate = *flagsim::ParameterTable::Get().Find("frame_rate");
    if (!(options.render_fps > 0) || options.render_fps > rate.max_value) {
      throw flagsim::SceneError("--fps: " + rate.Format(options.render_fps) +
                                " is out of range; a render draws frames, so allowed above 0 .. " +
                                rate.Format(rate.max_value) + " " + rate.unit);
    }
    assign("--fps", "frame_rate", options.render_fps);
  }
  if (options.render_threads > 0) assign("--threads", "threads", options.render_threads);
}

/// A render writes something and draws frames. Throws SceneError (a usage error) if not.
void CheckRender(const Options& options, const flagsim::Scene& scene) {
  if (options.render.log_path.empty() && options.render.png_dir.empty()) {
    throw flagsim::SceneError("render: nothing to write; give -o LOG, --png-dir DIR or both");
  }
  if (scene.service.frame_rate <= 0) {
    throw flagsim::SceneError(
        "render: frame_rate is 0 in the scene, so no frame would be drawn; give --fps F");
  }
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  CLI::App app{"flagd: a flag on a pole in the wind, simulated, steered and streamed over LCM"};
  app.add_option("--lcm-url", options.lcm_url,
                 "LCM URL (default: $LCM_DEFAULT_URL, else udpm://239.255.76.67:7667?ttl=0)");
  app.add_option("--prefix", options.prefix,
                 "channel prefix, so several servers share a bus: letters, digits and '_'")
      ->check(flagsim::ChannelPrefix())
      ->capture_default_str();
  CLI::Option* scene_option = app.add_option("--scene", options.scene,
                                             "a preset (breeze, calm, gale, hanging) or a scene file (.toml)")
                                  ->capture_default_str();
  CLI::Option* set_option =
      app.add_option("--set", options.assignments, "override a parameter: NAME=VALUE (repeatable)");
  app.add_flag("--fast", options.server.fast, "step as fast as possible instead of in real time");
  app.add_option(
         "--duration", options.server.duration,
         "stop after this many simulated seconds, counted from where it starts (0: run until stopped)")
      ->check(flagsim::ZeroOrMore());
  app.add_option("--record-inputs", options.server.inputs_log,
                 "also write what a replay needs (each applied command, the checkpoints) into this LCM "
                 "log, for `flagd replay` and `flagd --resume`");
  CLI::Option* resume =
      app.add_option("--resume", options.resume_log,
                     "start again from the last checkpoint in this log (a --record-inputs log of a server "
                     "that was killed or stopped), with the scene as it stood there; says how much came "
                     "after the checkpoint and is lost")
          ->check(CLI::ExistingFile);
  app.add_option(
         "--key-file", options.key_files,
         "take only commands signed with a key in this file (flagctl keygen -o FILE makes one; "
         "readable by its owner only); repeatable. Without it, anyone on the bus may steer the server")
      ->check(CLI::ExistingFile);
  app.add_option("--log-level", options.log_level, "trace, debug, info, warn, error or off")
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error", "off"}))
      ->capture_default_str();
  // A resumed session's scene is the checkpoint's; it is changed afterwards as any session is.
  resume->excludes(scene_option)->excludes(set_option);
  CLI::App* render = AddRenderCommand(app, options);
  CLI::App* replay = app.add_subcommand(
      "replay",
      "step a recorded session again from its log (its first CHECKPOINT, then the APPLIED commands at "
      "their steps) and check every recorded state hash bit for bit; exit 0 all equal, 1 a difference, "
      "2 nothing to replay");
  replay->add_option("log", options.replay_log, "the LCM log (flagctl record, lcm-logger, flagd render)")
      ->required();
  replay->add_option("--threads", options.replay.threads, "worker threads (default: as recorded)")
      ->check(CLI::Range(1, 64));
  replay->add_option("--prefix", options.prefix, "channel prefix in the log")->capture_default_str();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    return app.exit(error) == 0 ? 0 : 2;
  }
  // Logs go to stderr, as a command's diagnostics do; stdout is for what a command reports.
  spdlog::set_default_logger(
      std::make_shared<spdlog::logger>("", std::make_shared<spdlog::sinks::stderr_color_sink_mt>()));
  spdlog::set_level(spdlog::level::from_str(options.log_level));
  // Beside a busy neighbour, loops shared among more threads than the free cores run slower than
  // on one thread: share them among the free cores only.
  flagsim::WorkerPool::Shared().ShareFreeCoresOnly(true);
  if (!options.resume_log.empty() && (render->parsed() || replay->parsed())) {
    std::cerr << "flagd: --resume starts a server; it does not go with render or replay\n";
    return 2;
  }
  if (replay->parsed()) {
    options.replay.prefix = options.prefix;
    return flagsim::RunReplay(options.replay_log, options.replay);
  }

  flagsim::Scene scene;
  std::optional<flagsim::ResumePoint> resume_point;
  try {
    if (!options.resume_log.empty()) {
      resume_point = FindResume(options);
      scene = resume_point->snapshot.scene;
    } else {
      scene = BuildScene(options);
    }
    if (render->parsed()) {
      ApplyRenderOverrides(options, &scene);
      CheckRender(options, scene);
    }
  } catch (const flagsim::SceneError& error) {
    std::cerr << "flagd: " << error.what() << "\n";
    return 2;
  }
  if (render->parsed()) {
    std::signal(SIGINT, OnSignal);
    std::signal(SIGTERM, OnSignal);
    options.render.prefix = options.prefix;
    return flagsim::RunRender(scene, options.render, g_stop);
  }

  try {
    options.server.command_keys = ReadKeys(options.key_files);
  } catch (const std::exception& error) {
    std::cerr << "flagd: " << error.what() << "\n";
    return 2;
  }
  try {
    flagsim::Bus bus(flagsim::Bus::WithReceiveBuffer(options.lcm_url, 1 << 20));
    const flagsim::Channels channels(options.prefix);
    const std::unique_ptr<flagsim::Server> resumed_or_new =
        resume_point
            ? std::make_unique<flagsim::Server>(bus, channels, resume_point->snapshot, options.server)
            : std::make_unique<flagsim::Server>(bus, channels, scene, options.server);
    flagsim::Server& server = *resumed_or_new;
    if (resume_point && !ReportResume(options, *resume_point, server)) return 1;
    std::signal(SIGINT, OnSignal);
    std::signal(SIGTERM, OnSignal);
    spdlog::info("flagd: scene '{}' ({}x{} nodes), {} on {} with prefix {}", scene.name, scene.sim.cols,
                 scene.sim.rows, options.server.fast ? "as fast as possible" : "in real time", bus.url(),
                 channels.prefix);
    spdlog::info("flagd: command authentication: {}", server.authentication());
    if (!options.server.inputs_log.empty())
      spdlog::info("flagd: recording its inputs to {}", options.server.inputs_log);
    server.Run(g_stop);
    const auto& state = server.session().simulation().state();
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    spdlog::info("flagd: stopped at step {}, t = {:.3f} s, state hash {:016x}, peak memory {:.1f} MB",
                 state.step, state.time, server.session().simulation().Hash(), usage.ru_maxrss / 1024.0);
  } catch (const std::exception& error) {
    std::cerr << "flagd: " << error.what() << "\n";
    return 1;
  }
  return 0;
}
