// flagctl: the thin client. Steers a flagd server (wind, set, reset, camera, refresh), reads
// its streams (params, status, watch, snapshot) and records sessions (record).
// Exit codes: 0 ok, 2 usage, 3 rejected by the server (its reason printed), 4 no answer.
#include <CLI/CLI.hpp>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <iostream>
#include <optional>

#include "bus.hpp"
#include "channels.hpp"
#include "command_client.hpp"
#include "flagsim/camera_command_t.hpp"
#include "flagsim/frame_t.hpp"
#include "flagsim/param_command_t.hpp"
#include "flagsim/refresh_request_t.hpp"
#include "flagsim/wind_command_t.hpp"
#include "log_recorder.hpp"
#include "png_file.hpp"
#include "printing.hpp"
#include "stream_reader.hpp"
#include "tile_assembler.hpp"

namespace flagsim {
namespace {

enum ExitCode { kOk = 0, kUsage = 2, kRejected = 3, kNoAnswer = 4 };

std::atomic<bool> g_stop{false};
void OnSignal(int) { g_stop.store(true); }

struct Globals {
  std::string lcm_url;
  std::string prefix = Channels::kDefaultPrefix;
  double timeout = 2.0;  ///< s to wait for an answer
};

/// The bus and channels one subcommand talks on.
struct Link {
  explicit Link(const Globals& globals)
      : bus(Bus::WithReceiveBuffer(globals.lcm_url, 8 << 20)), channels(globals.prefix), globals(globals) {}
  Bus bus;
  Channels channels;
  const Globals& globals;

  int NoAnswer(const std::string& what) const {
    std::fprintf(stderr, "flagctl: no %s from a server with prefix %s on %s within %g s\n", what.c_str(),
                 channels.prefix.c_str(), bus.url().c_str(), globals.timeout);
    return kNoAnswer;
  }
};

int Report(const Link& link, const CommandOutcome& outcome) {
  switch (outcome.result) {
    case CommandOutcome::kAccepted:
      std::printf("accepted at step %lld\n", static_cast<long long>(outcome.step));
      return kOk;
    case CommandOutcome::kRejected:
      std::fprintf(stderr, "flagctl: rejected: %s\n", outcome.reason.c_str());
      return kRejected;
    case CommandOutcome::kNoAnswer: break;
  }
  return link.NoAnswer("answer");
}

int Wind(const Globals& globals, const std::vector<double>& velocity, double gust, double ramp) {
  Link link(globals);
  CommandClient client(link.bus, link.channels, globals.timeout);
  wind_command_t command{};
  for (int k = 0; k < 3; ++k) command.velocity[k] = velocity[k];
  command.gust = gust;
  command.ramp_time = ramp;
  return Report(link, client.Send(link.channels.wind, command));
}

int Set(const Globals& globals, const std::vector<std::string>& assignments, bool reset) {
  param_command_t command{};
  command.reset_to_scene = reset;
  for (const std::string& assignment : assignments) {
    const size_t equals = assignment.find('=');
    if (equals == std::string::npos || equals == 0) {
      std::fprintf(stderr, "flagctl: '%s' is not NAME=VALUE\n", assignment.c_str());
      return kUsage;
    }
    command.names.push_back(assignment.substr(0, equals));
    command.values.push_back(assignment.substr(equals + 1));
  }
  command.num_assignments = static_cast<int32_t>(command.names.size());
  Link link(globals);
  CommandClient client(link.bus, link.channels, globals.timeout);
  return Report(link, client.Send(link.channels.param, command));
}

int Refresh(const Globals& globals) {
  Link link(globals);
  CommandClient client(link.bus, link.channels, globals.timeout);
  std::optional<state_t> state;
  SubscribeDecoded<state_t>(link.bus, link.channels.state, [&state](const state_t& s) { state = s; });
  const CommandOutcome outcome = client.Send(link.channels.refresh, refresh_request_t{});
  if (outcome.result != CommandOutcome::kAccepted) return Report(link, outcome);
  state.reset();  // the full state published for this request comes after the ACK
  if (!HandleUntil(link.bus, globals.timeout, [&state] { return state.has_value(); })) {
    return link.NoAnswer("STATE");
  }
  std::printf("step %lld  t = %.3f s  %d x %d nodes  state hash %016llx\n", static_cast<long long>(state->step),
              state->sim_time, state->cols, state->rows, static_cast<unsigned long long>(state->state_hash));
  return kOk;
}

int Params(const Globals& globals) {
  Link link(globals);
  const auto params = AwaitMessage<params_t>(link.bus, link.channels.params, globals.timeout);
  if (!params) return link.NoAnswer("PARAMS");
  PrintParams(*params, std::cout);
  return kOk;
}

int Status(const Globals& globals) {
  Link link(globals);
  const auto status = AwaitMessage<status_t>(link.bus, link.channels.status, globals.timeout);
  if (!status) return link.NoAnswer("STATUS");
  PrintStatus(*status, std::cout);
  return kOk;
}

/// Prints one line a second about the STATE stream until `duration` (0: until interrupted).
int Watch(const Globals& globals, double duration) {
  Link link(globals);
  std::optional<state_t> latest;
  int64_t states = 0, state_bytes = 0, total_states = 0, invalid = 0;
  std::optional<status_t> status;
  SubscribeDecoded<state_t>(
      link.bus, link.channels.state,
      [&](const state_t& state) {
        latest = state;
        ++states;
        ++total_states;
        state_bytes += state.getEncodedSize();
      },
      &invalid, 1000);
  SubscribeDecoded<status_t>(link.bus, link.channels.status, [&status](const status_t& s) { status = s; }, &invalid);
  int64_t frames = 0, tiles = 0, tile_bytes = 0;
  SubscribeDecoded<frame_t>(link.bus, link.channels.frame, [&frames](const frame_t&) { ++frames; }, &invalid, 1000);
  SubscribeDecoded<tile_t>(
      link.bus, link.channels.tile,
      [&](const tile_t& tile) {
        ++tiles;
        tile_bytes += tile.num_bytes;
      },
      &invalid, 10000);
  const double start = MonotonicSeconds();
  double last_line = start;
  while (!g_stop.load()) {
    const double now = MonotonicSeconds();
    if (duration > 0 && now - start >= duration) break;
    if (total_states == 0 && now - start >= globals.timeout && duration == 0) break;
    link.bus.Handle(50);
    if (MonotonicSeconds() - last_line < 1.0 || !latest) continue;
    const double elapsed = MonotonicSeconds() - last_line;
    std::printf("t %9.3f s  step %8lld  STATE %5.1f Hz %6.1f KB  hash %016llx  tip %s",
                latest->sim_time, static_cast<long long>(latest->step), states / elapsed,
                states > 0 ? state_bytes / 1024.0 / states : 0.0,
                static_cast<unsigned long long>(latest->state_hash), TipText(*latest).c_str());
    if (status) std::printf("  rtf %.2f  step %.0f us", status->real_time_factor, status->step_time_us);
    if (frames > 0) {
      std::printf("  FRAME %4.1f Hz %5.1f tiles/frame %7.1f KB/s", frames / elapsed, double(tiles) / frames,
                  tile_bytes / 1024.0 / elapsed);
    }
    std::printf("\n");
    std::fflush(stdout);
    states = state_bytes = frames = tiles = tile_bytes = 0;
    last_line = MonotonicSeconds();
  }
  if (invalid > 0) std::fprintf(stderr, "flagctl: %lld undecodable message(s) ignored\n", static_cast<long long>(invalid));
  if (total_states == 0) return link.NoAnswer("STATE");
  std::printf("%lld states received\n", static_cast<long long>(total_states));
  return kOk;
}

/// Asks for a keyframe, assembles the tiles, checks the frame hash, writes a PNG.
int Snapshot(const Globals& globals, const std::string& path) {
  Link link(globals);
  CommandClient client(link.bus, link.channels, globals.timeout);
  TileAssembler assembler;
  bool complete = false, keyframe_incomplete = false;
  bool waiting = false;  // for frames after our request
  SubscribeDecoded<tile_t>(link.bus, link.channels.tile, [&](const tile_t& tile) { assembler.AddTile(tile); },
                           nullptr, 10000);
  SubscribeDecoded<frame_t>(
      link.bus, link.channels.frame,
      [&](const frame_t& manifest) {
        const auto result = assembler.AddManifest(manifest);
        if (!waiting) return;
        complete |= result == TileAssembler::FrameResult::kComplete;
        keyframe_incomplete |= manifest.keyframe && result != TileAssembler::FrameResult::kComplete;
      },
      nullptr, 1000);
  const double start = MonotonicSeconds(), deadline = start + globals.timeout;
  while (!complete) {
    // A keyframe that arrived with tiles missing calls for another request (a new id).
    keyframe_incomplete = false;
    const CommandOutcome outcome = client.Send(link.channels.refresh, refresh_request_t{});
    if (outcome.result != CommandOutcome::kAccepted) return Report(link, outcome);
    waiting = true;
    const double left = deadline - MonotonicSeconds();
    if (left <= 0 || !HandleUntil(link.bus, left, [&] { return complete || keyframe_incomplete; })) break;
  }
  if (!complete) return link.NoAnswer("complete frame");
  const std::string problem = WritePng(path, assembler.width(), assembler.height(), assembler.image().data());
  if (!problem.empty()) {
    std::fprintf(stderr, "flagctl: %s\n", problem.c_str());
    return 1;
  }
  std::printf("%s: %d x %d, frame %lld, complete %.0f ms after the request\n", path.c_str(), assembler.width(),
              assembler.height(), static_cast<long long>(assembler.last_complete_frame()),
              1000 * (MonotonicSeconds() - start));
  return kOk;
}

int Camera(const Globals& globals, camera_command_t command) {
  Link link(globals);
  CommandClient client(link.bus, link.channels, globals.timeout);
  return Report(link, client.Send(link.channels.camera, command));
}

/// Records every channel with the prefix to an LCM log until `duration` or an interrupt.
int Record(const Globals& globals, const std::string& path, double duration) {
  Link link(globals);
  std::unique_ptr<LogRecorder> recorder;
  try {
    recorder = std::make_unique<LogRecorder>(link.bus, link.channels.AllChannels(), path);
  } catch (const std::exception& error) {
    std::fprintf(stderr, "flagctl: %s\n", error.what());
    return kUsage;
  }
  const double start = MonotonicSeconds();
  while (!g_stop.load() && !recorder->failed()) {
    const double now = MonotonicSeconds();
    if (duration > 0 && now - start >= duration) break;
    if (recorder->events() == 0 && now - start >= globals.timeout && duration == 0) break;
    link.bus.Handle(50);
  }
  if (recorder->failed()) {
    std::fprintf(stderr, "flagctl: writing %s failed after %lld events\n", path.c_str(),
                 static_cast<long long>(recorder->events()));
    return 1;
  }
  std::printf("%s: %lld events, %.1f KB in %.1f s\n", path.c_str(), static_cast<long long>(recorder->events()),
              recorder->bytes() / 1024.0, MonotonicSeconds() - start);
  return recorder->events() > 0 ? kOk : link.NoAnswer("message");
}

}  // namespace
}  // namespace flagsim

int main(int argc, char** argv) {
  using namespace flagsim;
  Globals globals;
  CLI::App app{"flagctl: steer and watch a flagd server over LCM\n"
               "exit codes: 0 ok, 2 usage, 3 rejected by the server, 4 no answer within --timeout"};
  app.fallthrough();  // global options may follow the subcommand
  app.require_subcommand(1);
  app.add_option("--lcm-url", globals.lcm_url,
                 "LCM URL (default: $LCM_DEFAULT_URL, else udpm://239.255.76.67:7667?ttl=0)");
  app.add_option("--prefix", globals.prefix, "channel prefix of the server")->capture_default_str();
  app.add_option("--timeout", globals.timeout, "seconds to wait for an answer")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();

  std::vector<double> velocity;
  double gust = 0, ramp = 0;
  CLI::App* wind = app.add_subcommand("wind", "set the wind velocity (m/s, world frame: x along the flag, y up)");
  wind->add_option("velocity", velocity, "VX VY VZ in m/s")->expected(3)->required();
  wind->add_option("--gust", gust, "gust strength, fraction of the wind speed (0 .. 1)")->capture_default_str();
  wind->add_option("--ramp", ramp, "seconds of simulated time to reach this wind (0 .. 60)")->capture_default_str();

  std::vector<std::string> assignments;
  CLI::App* set = app.add_subcommand("set", "set parameters: NAME=VALUE ... (see flagctl params)");
  set->add_option("assignments", assignments, "NAME=VALUE pairs, applied together or not at all")->required();

  std::vector<std::string> reset_assignments;
  CLI::App* reset = app.add_subcommand("reset", "restore the scene's parameters and wind, flag at rest");
  reset->add_option("assignments", reset_assignments, "NAME=VALUE pairs to apply after the reset");

  app.add_subcommand("params", "print the parameter table with current values");
  app.add_subcommand("status", "print the server's health");
  app.add_subcommand("refresh", "request a full state (and frame) now");

  double watch_duration = 0;
  CLI::App* watch = app.add_subcommand("watch", "print the state stream, a line a second");
  watch->add_option("--duration", watch_duration, "seconds to watch (0: until interrupted)")
      ->check(CLI::NonNegativeNumber);

  std::string record_path;
  double record_duration = 0;
  CLI::App* record = app.add_subcommand("record", "record every channel of the server to an LCM log");
  record->add_option("-o,--output", record_path, "the log file to write")->required();
  record->add_option("--duration", record_duration, "seconds to record (0: until interrupted)")
      ->check(CLI::NonNegativeNumber);

  std::string snapshot_path;
  CLI::App* snapshot = app.add_subcommand("snapshot", "ask for a full frame and write it as a PNG");
  snapshot->add_option("-o,--output", snapshot_path, "the PNG file to write")->required();

  camera_command_t camera_command{};
  camera_command.factor = 1;
  CLI::App* camera = app.add_subcommand("camera", "move the camera (angles in degrees, distances in m)");
  camera->require_subcommand(1);
  double degrees = 0, degrees2 = 0;
  std::vector<double> point;
  const auto add_move = [&](const char* name, const char* help, int8_t operation) {
    CLI::App* move = camera->add_subcommand(name, help);
    move->callback([&camera_command, operation] { camera_command.operation = operation; });
    return move;
  };
  add_move("rotate-x", "turn the scene about the x axis through the target", camera_command_t::ROTATE_X)
      ->add_option("degrees", degrees)->required();
  add_move("rotate-y", "turn the scene about the y (up) axis through the target", camera_command_t::ROTATE_Y)
      ->add_option("degrees", degrees)->required();
  add_move("rotate-z", "turn the scene about the z axis through the target", camera_command_t::ROTATE_Z)
      ->add_option("degrees", degrees)->required();
  CLI::App* orbit = add_move("orbit", "move the eye around the target", camera_command_t::ORBIT);
  orbit->add_option("azimuth", degrees, "degrees")->required();
  orbit->add_option("elevation", degrees2, "degrees")->required();
  add_move("translate", "move eye and target by X Y Z", camera_command_t::TRANSLATE)
      ->add_option("offset", point, "X Y Z in m")->expected(3)->required();
  add_move("look-at", "aim at the point X Y Z", camera_command_t::LOOK_AT)
      ->add_option("point", point, "X Y Z in m")->expected(3)->required();
  CLI::App* scale = add_move("scale", "scale the scene about a point (default: the origin)", camera_command_t::SCALE);
  scale->add_option("factor", camera_command.factor, "2 doubles the apparent size")->required();
  scale->add_option("--about", point, "X Y Z in m")->expected(3);
  CLI::App* size = add_move("size", "set the image size", camera_command_t::SET_IMAGE_SIZE);
  size->add_option("width", camera_command.width, "px")->required();
  size->add_option("height", camera_command.height, "px")->required();
  add_move("reset", "back to the scene's camera", camera_command_t::RESET);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    return app.exit(error) == 0 ? kOk : kUsage;
  }
  camera_command.angle = degrees * M_PI / 180;
  camera_command.angle2 = degrees2 * M_PI / 180;
  for (size_t k = 0; k < point.size() && k < 3; ++k) camera_command.vector[k] = point[k];
  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);

  try {
    const std::string command = app.get_subcommands().front()->get_name();
    if (command == "wind") return Wind(globals, velocity, gust, ramp);
    if (command == "set") return Set(globals, assignments, false);
    if (command == "reset") return Set(globals, reset_assignments, true);
    if (command == "params") return Params(globals);
    if (command == "status") return Status(globals);
    if (command == "refresh") return Refresh(globals);
    if (command == "watch") return Watch(globals, watch_duration);
    if (command == "record") return Record(globals, record_path, record_duration);
    if (command == "snapshot") return Snapshot(globals, snapshot_path);
    if (command == "camera") return Camera(globals, camera_command);
  } catch (const std::exception& error) {
    std::fprintf(stderr, "flagctl: %s\n", error.what());
    return 1;
  }
  return kUsage;
}
