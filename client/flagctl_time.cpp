// flagctl time: the simulation's clock. pause, resume and step go out as TIME commands; scale
// sets the time_scale parameter (PARAM), simulated seconds per wall-clock second.
#include <memory>
#include <string>

#include "client/flagctl_commands.hpp"
#include "client/flagctl_link.hpp"
#include "flagsim/time_command_t.hpp"

namespace flagsim {
namespace {

void AddClockMove(CLI::App* time, Invocation& invocation, const char* name, const char* help, int8_t operation) {
  CLI::App* move = time->add_subcommand(name, help);
  invocation.RunOnParse(move, [&invocation, operation] {
    time_command_t command{};
    command.operation = operation;
    return SendCommand(invocation.globals, &Channels::time, command);
  });
}

void AddStep(CLI::App* time, Invocation& invocation) {
  CLI::App* step = time->add_subcommand("step", "take N steps of dt, then stay paused (pauses a running clock)");
  auto steps = std::make_shared<int32_t>(1);
  step->add_option("N", *steps, "how many steps (1 .. 100000)")->capture_default_str();
  invocation.RunOnParse(step, [&invocation, steps] {
    time_command_t command{};
    command.operation = time_command_t::STEP;
    command.steps = *steps;
    return SendCommand(invocation.globals, &Channels::time, command);
  });
}

void AddScale(CLI::App* time, Invocation& invocation) {
  CLI::App* scale = time->add_subcommand(
      "scale", "run at S simulated seconds per wall-clock second (the time_scale parameter; a reset leaves it)");
  auto value = std::make_shared<std::string>();
  scale->add_option("S", *value, "0.1 .. 4; 1 is real time")->required();
  invocation.RunOnParse(scale, [&invocation, value] { return SendParams(invocation.globals, {"time_scale=" + *value}, false); });
}

}  // namespace

void AddTimeCommand(CLI::App& app, Invocation& invocation) {
  CLI::App* time = app.add_subcommand(
      "time", "pause, step or resume the simulation, or run it slower or faster than real time; frames go on");
  time->require_subcommand(1);
  AddClockMove(time, invocation, "pause", "hold the flag still; frames, camera moves and parameters go on",
               time_command_t::PAUSE);
  AddClockMove(time, invocation, "resume", "run the clock again (at time_scale)", time_command_t::RESUME);
  AddStep(time, invocation);
  AddScale(time, invocation);
}

}  // namespace flagsim
