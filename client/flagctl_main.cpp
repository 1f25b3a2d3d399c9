// flagctl: the thin client. Steers a flagd server (wind, set, reset, camera, keyframe, refresh),
// reads its streams (params, status, watch, snapshot, keyframe list), records sessions (record),
// turns logs into pictures (export) and serves the live view to browsers (serve). This file is the command
// line; flagctl_commands.cpp, flagctl_keyframe.cpp and flagctl_export.cpp do the work. Exit codes: 0 ok, 1
// failed, 2 usage, 3 rejected by the server (its reason printed), 4 no answer, 5 nothing to export.
#include <CLI/CLI.hpp>
#include <cmath>
#include <csignal>
#include <cstdio>

#include "client/flagctl_commands.hpp"
#include "client/flagctl_keyframe.hpp"
#include "messages/channels.hpp"
#include "messages/command_key.hpp"

namespace {

void OnSignal(int) { flagsim::g_stop.store(true); }

}  // namespace

int main(int argc, char** argv) {
  using namespace flagsim;
  Globals globals;
  CLI::App app{
      "flagctl: steer and watch a flagd server over LCM\n"
      "exit codes: 0 ok, 1 failed (a file, ffmpeg), 2 usage, 3 rejected by the server, 4 no answer within "
      "--timeout, 5 nothing to export"};
  app.fallthrough();  // global options may follow the subcommand
  app.require_subcommand(1);
  app.add_option("--lcm-url", globals.lcm_url,
                 "LCM URL (default: $LCM_DEFAULT_URL, else udpm://239.255.76.67:7667?ttl=0)");
  app.add_option("--prefix", globals.prefix, "channel prefix of the server")->capture_default_str();
  app.add_option("--timeout", globals.timeout, "seconds to wait for an answer")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  std::string key_file;
  app.add_option("--key-file", key_file,
                 "sign every command with the first key in this file (flagctl keygen), for a server "
                 "started with --key-file; also $FLAGSIM_KEY_FILE")
      ->envname("FLAGSIM_KEY_FILE");

  std::string keygen_path, keygen_name = "flagsim";
  CLI::App* keygen = app.add_subcommand(
      "keygen", "write a new key file for signed commands (flagd --key-file, flagctl --key-file)");
  keygen->add_option("-o,--output", keygen_path, "the key file to create (never overwritten; mode 600)")
      ->required();
  keygen->add_option("--name", keygen_name, "the key's name, which commands carry and logs show")
      ->capture_default_str();

  std::vector<double> velocity;
  double gust = 0, ramp = 0;
  CLI::App* wind =
      app.add_subcommand("wind", "set the wind velocity (m/s, world frame: x along the flag, y up)");
  wind->add_option("velocity", velocity, "VX VY VZ in m/s")->expected(3)->required();
  wind->add_option("--gust", gust, "gust strength, fraction of the wind speed (0 .. 1)")
      ->capture_default_str();
  wind->add_option("--ramp", ramp, "seconds of simulated time to reach this wind (0 .. 60)")
      ->capture_default_str();

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

  ExportRequest export_request;
  CLI::App* export_command =
      app.add_subcommand("export", "turn the frames in an LCM log into PNGs, an MP4 or a GIF");
  export_command
      ->add_option("log", export_request.log_path, "the log (flagctl record, flagd render, lcm-logger)")
      ->required();
  export_command
      ->add_option(
          "-o,--output", export_request.output,
          "DIR/ or an existing directory: PNG frames frame_%06d.png; NAME.mp4: H.264 video; NAME.gif")
      ->required();
  export_command
      ->add_option(
          "--fps", export_request.frame_rate,
          "frames per second of the video (default: the log's frame rate, from its PARAMS or FRAME times)")
      ->check(CLI::PositiveNumber);
  export_command->footer(
      "Reads the TILE and FRAME events with the prefix (--prefix) and assembles them as a client\n"
      "would; every frame written has the server's frame hash. A log recorded mid-stream starts at its\n"
      "first keyframe (earlier frames are skipped, with a note). The log's timing is kept: a frame whose\n"
      "tiles were lost (its hash does not check out), and a frame time the server skipped, repeat the\n"
      "last whole frame, so there is one image per frame time. A log cut short (a recorder killed\n"
      "mid-write) is exported up to its last whole event, with a message naming the byte and event where\n"
      "it stops. Videos are made by ffmpeg (Debian's ffmpeg package) and keep the first frame's size.\n"
      "Exit codes: 0 ok (also for a log cut short), 1 ffmpeg missing or failed or a file not written,\n"
      "2 usage, 5 no complete frame in the log.");

  std::string snapshot_path;
  CLI::App* snapshot = app.add_subcommand("snapshot", "ask for a full frame and write it as a PNG");
  snapshot->add_option("-o,--output", snapshot_path, "the PNG file to write")->required();

  camera_command_t camera_command{};
  camera_command.factor = 1;
  CLI::App* camera = app.add_subcommand(
      "camera", "move the camera (angles in degrees, distances in m); the eye stays above the ground");
  camera->require_subcommand(1);
  double degrees = 0, degrees2 = 0;
  std::vector<double> point;
  const auto add_move = [&](const char* name, const char* help, int8_t operation) {
    CLI::App* move = camera->add_subcommand(name, help);
    move->callback([&camera_command, operation] { camera_command.operation = operation; });
    return move;
  };
  add_move("rotate-x", "turn the scene about the x axis through the target", camera_command_t::ROTATE_X)
      ->add_option("degrees", degrees, "the angle in degrees, right-handed about +x")
      ->required();
  add_move("rotate-y", "turn the scene about the y (up) axis through the target", camera_command_t::ROTATE_Y)
      ->add_option("degrees", degrees, "the angle in degrees, right-handed about +y")
      ->required();
  add_move("rotate-z", "turn the scene about the z axis through the target", camera_command_t::ROTATE_Z)
      ->add_option("degrees", degrees, "the angle in degrees, right-handed about +z")
      ->required();
  CLI::App* orbit =
      add_move("orbit", "move the eye around the target; it stops at the ground rather than going under",
               camera_command_t::ORBIT);
  orbit->add_option("azimuth", degrees, "degrees around the vertical axis through the target")->required();
  orbit->add_option("elevation", degrees2, "degrees up (negative: down); the eye stops at the ground")
      ->required();
  add_move("zoom", "move the eye along the line to the target (kept 0.1 .. 200 m from it)",
           camera_command_t::ZOOM)
      ->add_option("factor", camera_command.factor,
                   "the distance is divided by it: 2 twice as close, 0.5 twice as far")
      ->required();
  add_move("translate", "move eye and target by X Y Z", camera_command_t::TRANSLATE)
      ->add_option("offset", point, "X Y Z in m")
      ->expected(3)
      ->required();
  add_move("look-at", "aim at the point X Y Z", camera_command_t::LOOK_AT)
      ->add_option("point", point, "X Y Z in m")
      ->expected(3)
      ->required();
  add_move("eye", "put the eye at X Y Z, looking at the same target", camera_command_t::SET_EYE)
      ->add_option("point", point, "X Y Z in m (y up, at least 0.05 above the ground)")
      ->expected(3)
      ->required();
  add_move("fov", "set the vertical field of view", camera_command_t::SET_FOV)
      ->add_option("degrees", degrees, "10 .. 120 degrees")
      ->required();
  CLI::App* scale = camera->add_subcommand(
      "scale",
      "zoom toward the target (as zoom); with --about, scale the scene about that point instead (the seed's "
      "transform)");
  scale->add_option("factor", camera_command.factor, "2: twice as close, or twice the size about the point")
      ->required();
  CLI::Option* about =
      scale->add_option("--about", point, "X Y Z in m: the point to scale the scene about")->expected(3);
  scale->callback([&camera_command, about] {
    camera_command.operation = about->count() > 0 ? camera_command_t::SCALE : camera_command_t::ZOOM;
  });
  CLI::App* size = add_move("size", "set the image size", camera_command_t::SET_IMAGE_SIZE);
  size->add_option("width", camera_command.width, "px")->required();
  size->add_option("height", camera_command.height, "px")->required();
  add_move("reset", "back to the scene's camera", camera_command_t::RESET);

  KeyframeArguments keyframe;
  AddKeyframeCommand(app, &keyframe);

  gateway::ServeOptions serve_options;
  CLI::App* serve = app.add_subcommand(
      "serve",
      "serve the live view to browsers and Foxglove (the Foxglove WebSocket protocol) until interrupted");
  serve->add_option("--listen", serve_options.listen, "HOST:PORT to listen on (port 0: any free one)")
      ->capture_default_str();
  serve
      ->add_option(
          "--token", serve_options.token,
          "required on every request (?token=, a bearer header, or the page's cookie); generated when "
          "listening beyond loopback without one; from $FLAGSIM_TOKEN if set, which keeps it out of "
          "process listings")
      ->envname("FLAGSIM_TOKEN");
  serve->add_option(
      "--allow-origin", serve_options.allow_origins,
      "a browser origin allowed besides the gateway's own, e.g. https://app.foxglove.dev; * for any");
  serve->add_option("--record-dir", serve_options.record_directory, "where the page's recordings go")
      ->capture_default_str();
  serve->footer(
      "Commands from browsers go out as WIND, PARAM, CAMERA, KEYFRAME and REFRESH and are answered with\n"
      "the server's ACK; --timeout is how long the gateway waits for one. The protocol, channels and\n"
      "services are in docs/live-view.md.");

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
  if (keygen->parsed()) return Keygen(keygen_path, keygen_name);
  if (!key_file.empty()) {
    try {
      globals.signer = CommandSigner(ReadKeyFile(key_file).front());
    } catch (const std::exception& error) {
      std::fprintf(stderr, "flagctl: %s\n", error.what());
      return kFailed;
    }
  }

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
    if (command == "export") return Export(globals, export_request);
    if (command == "keyframe") return Keyframe(globals, keyframe);
    if (command == "serve") return Serve(globals, serve_options);
  } catch (const std::exception& error) {
    std::fprintf(stderr, "flagctl: %s\n", error.what());
    return 1;
  }
  return kUsage;
}
