// flagctl keyframe: the animation timeline's subcommands, their command line and what they do.
//   keyframe add T [--wind VX VY VZ [--gust G]] [--set NAME=VALUE ...]
//                  [--eye X Y Z --target X Y Z --fov F] [--law step|linear|smooth|cubic]
//   keyframe change T [--time T2] [the options of add]   the key's other controls stay
//   keyframe remove T | clear | list | play | pause | seek T | loop on|off | speed S
// Exit codes as every subcommand's: 0 ok, 2 usage, 3 rejected (the reason printed), 4 no answer.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "client/flagctl_commands.hpp"

namespace flagsim {

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

/// Adds `keyframe` and its subcommands to `app`, filling `arguments` when parsed.
CLI::App* AddKeyframeCommand(CLI::App& app, KeyframeArguments* arguments);

/// Sends the command (or, for list, prints the TIMELINE stream's next message).
int Keyframe(const Globals& globals, const KeyframeArguments& arguments);

}  // namespace flagsim
