#include "server/service/replay.hpp"

#include <cinttypes>
#include <cstdio>
#include <memory>
#include <optional>

#include "flagsim/applied_command_t.hpp"
#include "flagsim/design_piece_t.hpp"
#include "flagsim/state_t.hpp"
#include "messages/channels.hpp"
#include "messages/checked_decode.hpp"
#include "messages/event_log_reader.hpp"
#include "server/service/checkpoint_codec.hpp"
#include "server/service/command_apply.hpp"
#include "server/service/journal.hpp"

namespace flagsim {
namespace {

constexpr size_t kMaxMessageBytes = 256 << 20;  ///< a checkpoint of the largest grid fits
/// Steps the replay takes at most to reach the next event. A sound log has a CHECKPOINT every
/// Journal::kCheckpointSteps; this allows three in a row lost on the way to the recorder. An
/// event further ahead (a damaged step number) would keep the replay stepping for ever.
constexpr int64_t kMaxStepsAhead = 4 * Journal::kCheckpointSteps;

std::string Hex(uint64_t value) {
  char text[20];
  std::snprintf(text, sizeof(text), "%016" PRIx64, value);
  return text;
}

/// The replayed session and where the log stands.
class Replayer {
 public:
  Replayer(const ReplayOptions& options, ReplayReport* report) : options_(options), report_(*report) {}

  /// Handles one event; false once replay must stop (a difference, or a new session).
  bool Handle(const std::string& channel, const std::vector<uint8_t>& data);
  bool started() const { return session_ != nullptr; }

 private:
  template <class Message>
  std::optional<Message> Decode(const std::vector<uint8_t>& data) const {
    std::string error;
    return wire::CheckedDecode<Message>(data.data(), data.size(), kMaxMessageBytes, &error);
  }
  bool Resume(const checkpoint_t& checkpoint);
  /// Steps on to `step` (if ahead) for an event on `channel`; false (the log ends there) if it
  /// lies further ahead than a sound log's events do.
  bool AdvanceTo(int64_t step, const std::string& channel);
  bool Check(const char* what, int64_t step, uint64_t recorded);
  bool Apply(const applied_command_t& command);
  bool Differ(int64_t step, const std::string& what);

  ReplayOptions options_;
  ReplayReport& report_;
  Channels channels_{options_.prefix};
  std::unique_ptr<Session> session_;
  DesignLibrary designs_;  ///< the design files the log holds so far (DESIGN_FILE)
};

bool Replayer::Handle(const std::string& channel, const std::vector<uint8_t>& data) {
  if (channel == channels_.design_file) {
    const std::optional<design_piece_t> piece = Decode<design_piece_t>(data);
    if (piece) designs_.Add(*piece);  // a bad one: whatever needs its file says so
    return true;
  }
  if (channel == channels_.checkpoint) {
    const std::optional<checkpoint_t> checkpoint = Decode<checkpoint_t>(data);
    if (!checkpoint) return true;  // a damaged one: the next will do
    if (!started()) return Resume(*checkpoint);
    if (checkpoint->step < session_->simulation().state().step || checkpoint->reason == "start") {
      report_.log_end = "a new session starts at step " + std::to_string(checkpoint->step) + " (" +
                        checkpoint->reason + " checkpoint); replayed the first";
      return false;
    }
    if (!AdvanceTo(checkpoint->step, channel)) return false;
    report_.last_checkpoint_step = checkpoint->step;
    report_.last_checkpoint_hash = uint64_t(checkpoint->state_hash);
    return Check("checkpoint", checkpoint->step, uint64_t(checkpoint->state_hash));
  }
  if (!started()) return true;
  if (channel == channels_.applied) {
    const std::optional<applied_command_t> command = Decode<applied_command_t>(data);
    return !command || Apply(*command);
  }
  if (channel == channels_.state) {
    const std::optional<state_t> state = Decode<state_t>(data);
    if (!state) return true;
    if (state->step < session_->simulation().state().step) {
      ++report_.skipped;
      return true;
    }
    return AdvanceTo(state->step, channel) && Check("state", state->step, uint64_t(state->state_hash));
  }
  return true;
}

bool Replayer::Resume(const checkpoint_t& checkpoint) {
  SessionSnapshot snapshot;
  const std::string problem = ReadCheckpoint(checkpoint, &snapshot, &designs_);
  if (!problem.empty()) {
    report_.error = problem;
    return false;
  }
  if (options_.threads > 0)
    snapshot.scene.sim.threads = snapshot.simulation.params.threads = options_.threads;
  session_ = std::make_unique<Session>(snapshot);
  report_.first_step = report_.last_step = checkpoint.step;
  report_.first_reason = checkpoint.reason;
  report_.first_hash = uint64_t(checkpoint.state_hash);
  report_.threads = snapshot.simulation.params.threads;
  return true;
}

bool Replayer::AdvanceTo(int64_t step, const std::string& channel) {
  const int64_t now = session_->simulation().state().step;
  if (step - now > kMaxStepsAhead) {
    report_.log_end = channel + " at step " + std::to_string(step) + ", " + std::to_string(step - now) +
                      " steps past the replay at step " + std::to_string(now) +
                      " with nothing recorded between " + "(a sound log has a CHECKPOINT every " +
                      std::to_string(Journal::kCheckpointSteps) +
                      " steps): the log is damaged there; replayed up to it";
    return false;
  }
  while (session_->simulation().state().step < step) session_->Step();
  report_.last_step = session_->simulation().state().step;
  return true;
}

bool Replayer::Check(const char* what, int64_t step, uint64_t recorded) {
  const uint64_t replayed = session_->simulation().Hash();
  (std::string(what) == "state" ? report_.states_checked : report_.checkpoints_checked) += 1;
  if (replayed == recorded) return true;
  return Differ(step, std::string(what) + " hash at step " + std::to_string(step) + ": recorded " +
                          Hex(recorded) + ", replayed " + Hex(replayed));
}

bool Replayer::Apply(const applied_command_t& command) {
  if (command.step < session_->simulation().state().step) {
    return Differ(command.step, command.channel + " applied at step " + std::to_string(command.step) +
                                    ", behind the replay at step " +
                                    std::to_string(session_->simulation().state().step));
  }
  if (!AdvanceTo(command.step, channels_.applied)) return false;
  ++(command.channel == "MODEL" ? report_.model_switches : report_.commands);
  const std::string problem = ApplyCommandBytes(command.channel, command.data, session_.get(), &designs_);
  if (problem.empty()) return true;
  return Differ(command.step, command.channel + " at step " + std::to_string(command.step) +
                                  " was applied live but not in the replay: " + problem);
}

bool Replayer::Differ(int64_t step, const std::string& what) {
  report_.divergence = what;
  report_.divergence_step = step;
  return false;
}

}  // namespace

ReplayReport Replay(const std::string& path, const ReplayOptions& options,
                    const std::function<void(double)>& progress) {
  ReplayReport report;
  std::unique_ptr<EventLogReader> reader;
  try {
    reader = std::make_unique<EventLogReader>(path);
  } catch (const std::exception& error) {
    report.error = error.what();
    return report;
  }
  Replayer replayer(options, &report);
  const Channels channels(options.prefix);
  const auto wanted = [&channels](const std::string& channel) {
    return channel == channels.checkpoint || channel == channels.applied || channel == channels.state ||
           channel == channels.design_file;
  };
  LogEvent event;
  int64_t events = 0;
  bool going = true;
  while (going && reader->Next(&event, wanted)) {
    if (wanted(event.channel)) going = replayer.Handle(event.channel, event.data);
    if (progress && ++events % 256 == 0 && reader->size() > 0)
      progress(double(reader->offset()) / reader->size());
  }
  if (going && reader->end() != EventLogReader::End::kClean) report.log_end = reader->problem();
  if (report.error.empty() && !replayer.started()) {
    // Where the reader stopped early ("LOG: at byte 0, event 0: not an LCM event log (...)") says
    // more than that no checkpoint came before it.
    const std::string none = "no whole CHECKPOINT on " + channels.checkpoint;
    report.error =
        (report.log_end.empty() ? path + ": " + none : report.log_end + "; " + none + " before it") +
        " (a log recorded from a server that publishes checkpoints, with the same --prefix)";
  }
  if (progress) progress(1.0);
  return report;
}

}  // namespace flagsim
