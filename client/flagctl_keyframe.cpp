// flagctl keyframe: the animation timeline's subcommands, their command line and what they do.
//   keyframe add T [--wind VX VY VZ [--gust G]] [--set NAME=VALUE ...]
//                  [--eye X Y Z --target X Y Z --fov F] [--law step|linear|smooth|cubic]
//   keyframe change T [--time T2] [the options of add]   the key's other controls stay
//   keyframe remove T | clear | list | play | pause | seek T | loop on|off | speed S
// Exit codes as every subcommand's: 0 ok, 2 usage, 3 rejected (the reason printed), 4 no answer.
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "client/flagctl_commands.hpp"
#include "client/flagctl_link.hpp"
#include "client/printing.hpp"
#include "flagsim/keyframe_command_t.hpp"
#include "flagsim/timeline_t.hpp"

namespace flagsim {
namespace {

/// What the keyframe subcommands were given on the command line.
struct KeyframeArguments {
  std::string operation;     ///< the subcommand's name: add, change, remove, ...
  double time = 0;           ///< s of timeline time: the key (add, change, remove), the seek target
  double new_time = 0;       ///< change --time: s, where the key moves
  std::vector<double> wind;  ///< m/s, VX VY VZ; empty: the key sets no wind
  double gust = 0;           ///< fraction of the wind speed
  std::vector<std::string> assignments;  ///< NAME=VALUE, parameters the key sets
  std::vector<double> eye, target;       ///< m, X Y Z; empty: the key sets no camera
  double fov = 40;                       ///< degrees, vertical
  std::string law;                       ///< step, linear, smooth, cubic; empty: linear (add), kept (change)
  std::string loop;                      ///< on or off
  double speed = 1;                      ///< timeline s per simulated s
};

const std::vector<std::string> kLaws = {"step", "linear", "smooth", "cubic"};  // LAW_* order

/// --wind, --gust, --set, --eye, --target, --fov and --law, for add and change.
void AddKeyOptions(CLI::App* command, KeyframeArguments* arguments) {
  CLI::Option* wind =
      command->add_option("--wind", arguments->wind, "VX VY VZ in m/s (x along the flag, y up)")->expected(3);
  command->add_option("--gust", arguments->gust, "gust strength, fraction of the wind speed (0 .. 1)")
      ->needs(wind);
  command->add_option("--set", arguments->assignments,
                      "NAME=VALUE: a coefficient of the forces (a parameter a key may move; the server "
                      "names them if NAME is not one)");
  CLI::Option* eye = command->add_option("--eye", arguments->eye, "X Y Z in m: the camera")->expected(3);
  CLI::Option* target =
      command->add_option("--target", arguments->target, "X Y Z in m: looked at")->expected(3);
  CLI::Option* fov = command->add_option("--fov", arguments->fov, "degrees, vertical (10 .. 120)");
  eye->needs(target, fov);
  target->needs(eye, fov);
  fov->needs(eye, target);
  command->add_option("--law", arguments->law, "how the key's controls move on to the next key's")
      ->check(CLI::IsMember(kLaws));
}

/// The key the options describe; "" or what is wrong with them (a usage error).
std::string BuildKey(const KeyframeArguments& arguments, timeline_key_t* key) {
  key->time =
      arguments.operation == "change" && arguments.new_time >= 0 ? arguments.new_time : arguments.time;
  key->law = timeline_key_t::LAW_LINEAR;
  for (size_t law = 0; law < kLaws.size(); ++law) {
    if (arguments.law == kLaws[law]) key->law = static_cast<int8_t>(law);
  }
  key->has_wind = !arguments.wind.empty();
  for (size_t k = 0; k < arguments.wind.size() && k < 3; ++k) key->wind_velocity[k] = arguments.wind[k];
  key->wind_gust = arguments.gust;
  for (const std::string& assignment : arguments.assignments) {
    const size_t equals = assignment.find('=');
    const std::string value = equals == std::string::npos ? "" : assignment.substr(equals + 1);
    char* end = nullptr;
    const double number = std::strtod(value.c_str(), &end);
    if (equals == std::string::npos || equals == 0 || value.empty() || *end != '\0') {
      return "'" + assignment + "' is not NAME=NUMBER";
    }
    key->names.push_back(assignment.substr(0, equals));
    key->values.push_back(number);
  }
  key->num_parameters = static_cast<int32_t>(key->names.size());
  key->has_camera = !arguments.eye.empty();
  for (size_t k = 0; k < 3 && key->has_camera; ++k) {
    key->camera_eye[k] = arguments.eye[k];
    key->camera_target[k] = arguments.target[k];
  }
  key->camera_fov = arguments.fov;
  return "";
}

int8_t OperationCode(const std::string& operation) {
  if (operation == "add") return keyframe_command_t::ADD;
  if (operation == "change") return keyframe_command_t::CHANGE;
  if (operation == "remove") return keyframe_command_t::REMOVE;
  if (operation == "clear") return keyframe_command_t::CLEAR;
  if (operation == "play") return keyframe_command_t::PLAY;
  if (operation == "pause") return keyframe_command_t::PAUSE;
  if (operation == "seek") return keyframe_command_t::SEEK;
  if (operation == "loop") return keyframe_command_t::LOOP;
  return keyframe_command_t::SPEED;
}

/// The command the arguments describe, sent (or, for list, the TIMELINE stream's next message
/// printed): the exit code.
int Keyframe(const Globals& globals, const KeyframeArguments& arguments) {
  if (arguments.operation == "list") {
    return AwaitAndPrint<timeline_t>(globals, &Channels::timeline, "TIMELINE",
                                     [](const timeline_t& message) { PrintTimeline(message, std::cout); });
  }
  keyframe_command_t command{};
  command.operation = OperationCode(arguments.operation);
  command.time = arguments.time;
  command.speed = arguments.speed;
  command.loop = arguments.loop == "on";
  command.keep_law = arguments.operation == "change" && arguments.law.empty();
  if (arguments.operation == "add" || arguments.operation == "change") {
    const std::string problem = BuildKey(arguments, &command.key);
    if (!problem.empty()) {
      std::fprintf(stderr, "flagctl: %s\n", problem.c_str());
      return kUsage;
    }
  }
  return SendCommand(globals, &Channels::keyframe, command);
}

}  // namespace

void AddKeyframeCommand(CLI::App& app, Invocation& invocation) {
  const auto shared = std::make_shared<KeyframeArguments>();
  KeyframeArguments* arguments = shared.get();
  CLI::App* keyframe = app.add_subcommand("keyframe", "edit and play the animation timeline (times in s)");
  keyframe->require_subcommand(1);
  const auto add = [&](const char* name, const char* help) {
    CLI::App* command = keyframe->add_subcommand(name, help);
    invocation.RunOnParse(command, [&invocation, shared, name] {
      shared->operation = name;
      return Keyframe(invocation.globals, *shared);
    });
    return command;
  };
  CLI::App* add_key = add("add", "add a key at T s (replacing one there): any of wind, parameters, camera");
  add_key->add_option("time", arguments->time, "s of timeline time")->required();
  AddKeyOptions(add_key, arguments);
  CLI::App* change = add("change", "change the key at T s: the controls given replace its own");
  change->add_option("time", arguments->time, "s of timeline time: the key")->required();
  arguments->new_time = -1;
  change->add_option("--time", arguments->new_time, "s: move the key there");
  AddKeyOptions(change, arguments);
  add("remove", "remove the key at T s")->add_option("time", arguments->time, "s")->required();
  add("clear", "remove every key");
  add("list", "print the timeline: keys, what each sets, play state");
  add("play", "play from the position: the keys drive the controls they set");
  add("pause", "stop at the position; commands drive the controls again");
  add("seek", "move the position to T s")->add_option("time", arguments->time, "s")->required();
  add("loop", "wrap to 0 at the last key, or stop there")
      ->add_option("state", arguments->loop, "on or off")
      ->required()
      ->check(CLI::IsMember({"on", "off"}));
  add("speed", "timeline seconds per simulated second")
      ->add_option("speed", arguments->speed, "above 0, up to 100")
      ->required();
}

}  // namespace flagsim
