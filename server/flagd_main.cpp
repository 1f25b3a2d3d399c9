// flagd: the flag simulation server. Steps the flag in real time (or as fast as it can), draws
// and streams its frames as tiles, publishes STATE, PARAMS and STATUS, and takes WIND, PARAM,
// CAMERA and REFRESH commands over LCM.
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <atomic>
#include <sys/resource.h>

#include <csignal>
#include <iostream>

#include "bus.hpp"
#include "channels.hpp"
#include "parameter_table.hpp"
#include "scene_file.hpp"
#include "service/server.hpp"

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
};

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
  const std::string problem = flagsim::ParameterTable::CheckConsistency(scene);
  if (!problem.empty()) throw flagsim::SceneError(problem);
  return scene;
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  CLI::App app{"flagd: a flag on a pole in the wind, simulated, steered and streamed over LCM"};
  app.add_option("--lcm-url", options.lcm_url,
                 "LCM URL (default: $LCM_DEFAULT_URL, else udpm://239.255.76.67:7667?ttl=0)");
  app.add_option("--prefix", options.prefix, "channel prefix, so several servers share a bus")
      ->capture_default_str();
  app.add_option("--scene", options.scene, "a preset (breeze, calm, gale, hanging) or a scene file (.toml)")
      ->capture_default_str();
  app.add_option("--set", options.assignments, "override a parameter: NAME=VALUE (repeatable)");
  app.add_flag("--fast", options.server.fast, "step as fast as possible instead of in real time");
  app.add_option("--duration", options.server.duration,
                 "stop after this many simulated seconds (0: run until stopped)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--log-level", options.log_level, "trace, debug, info, warn, error or off")
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error", "off"}))
      ->capture_default_str();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    return app.exit(error) == 0 ? 0 : 2;
  }
  spdlog::set_level(spdlog::level::from_str(options.log_level));

  flagsim::Scene scene;
  try {
    scene = BuildScene(options);
  } catch (const flagsim::SceneError& error) {
    std::cerr << "flagd: " << error.what() << "\n";
    return 2;
  }

  try {
    flagsim::Bus bus(flagsim::Bus::WithReceiveBuffer(options.lcm_url, 1 << 20));
    const flagsim::Channels channels(options.prefix);
    flagsim::Server server(bus, channels, scene, options.server);
    std::signal(SIGINT, OnSignal);
    std::signal(SIGTERM, OnSignal);
    spdlog::info("flagd: scene '{}' ({}x{} nodes), {} on {} with prefix {}", scene.name, scene.sim.cols,
                 scene.sim.rows, options.server.fast ? "as fast as possible" : "in real time", bus.url(),
                 channels.prefix);
    server.Run(g_stop);
    const auto& state = server.session().simulation().state();
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    spdlog::info("flagd: stopped at step {}, t = {:.3f} s, state hash {:016x}, peak memory {:.1f} MB", state.step,
                 state.time, server.session().simulation().Hash(), usage.ru_maxrss / 1024.0);
  } catch (const std::exception& error) {
    std::cerr << "flagd: " << error.what() << "\n";
    return 1;
  }
  return 0;
}
