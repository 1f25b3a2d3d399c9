// The corpus's live session: the commands flagctl sends (built as flagctl builds them), and a
// server on an in-process bus and a simulated clock, steered by flagctl's command client through
// a keyframe request, wind, parameters, an orbit, a played timeline and a question, recorded by
// flagctl record's recorder. Its log is the event log and replay seed, and its messages by
// channel the command, stream and checkpoint seeds (make_corpus.cpp).
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "flagsim/camera_command_t.hpp"
#include "flagsim/keyframe_command_t.hpp"
#include "flagsim/time_command_t.hpp"
#include "flagsim/param_command_t.hpp"
#include "flagsim/refresh_request_t.hpp"
#include "flagsim/wind_command_t.hpp"
#include "messages/event_log_reader.hpp"
#include "messages/utime.hpp"
#include "server/scene/scene.hpp"

namespace flagsim::fuzz {

/// A small flag and small frames (two tiles), few frames and states: a log of some tens of KB.
Scene SessionScene();

/// The command as flagctl stamps it: now, client "flagctl-seed", the given sequence.
template <class Command>
Command Stamped(Command command, int64_t sequence) {
  command.utime = UnixMicros();
  command.client_id = "flagctl-seed";
  command.sequence = sequence;
  return command;
}

wind_command_t Wind(double vx, double vy, double vz, double gust, double ramp);
param_command_t Param(const std::vector<std::pair<std::string, std::string>>& assignments, bool reset = false);
camera_command_t Camera(int8_t operation);
keyframe_command_t Keyframe(int8_t operation);
/// A key at `time` setting wind, stiffness and damping, and the camera (as flagctl keyframe add).
keyframe_command_t KeyAdd(double time, int8_t law, bool camera);
/// A REFRESH that asks for the tables only.
refresh_request_t Question();
/// A TIME command: pause, resume, or `steps` steps.
time_command_t Time(int8_t operation, int32_t steps = 0);

/// Runs the session and records its bus into `log_path`.
void RecordSession(const std::string& log_path);
/// The session's events, in the log's order.
std::vector<LogEvent> ReadEvents(const std::string& log_path);

}  // namespace flagsim::fuzz
