#include "server/service/resume_point.hpp"

#include <cstdio>
#include <memory>
#include <optional>

#include "flagsim/applied_command_t.hpp"
#include "flagsim/design_piece_t.hpp"
#include "flagsim/state_t.hpp"
#include "flagsim/status_t.hpp"
#include "messages/channels.hpp"
#include "messages/checked_decode.hpp"
#include "messages/event_log_reader.hpp"
#include "server/service/checkpoint_codec.hpp"

namespace flagsim {
namespace {

constexpr size_t kMaxMessageBytes = 256 << 20;  ///< a checkpoint of the largest grid fits

template <class Message>
std::optional<Message> Decode(const std::vector<uint8_t>& data, std::string* error = nullptr) {
  std::string ignored;
  return wire::CheckedDecode<Message>(data.data(), data.size(), kMaxMessageBytes, error ? error : &ignored);
}

/// The resume point as the log is read: each sound checkpoint replaces it.
class ResumeSearch {
 public:
  explicit ResumeSearch(ResumePoint* point) : point_(*point) {}

  void Checkpoint(const std::vector<uint8_t>& data);
  /// A piece of a design file: checkpoints that show a person's image need it.
  void DesignPiece(const std::vector<uint8_t>& data) {
    if (const std::optional<design_piece_t> piece = Decode<design_piece_t>(data)) designs_.Add(*piece);
  }
  void Applied(const std::vector<uint8_t>& data);
  /// A message that says where the server stood (STATUS, STATE).
  void Progress(int64_t step, double sim_time);
  bool found() const { return point_.step >= 0; }

 private:
  ResumePoint& point_;
  DesignLibrary designs_;
};

void ResumeSearch::Checkpoint(const std::vector<uint8_t>& data) {
  std::string problem;
  const std::optional<checkpoint_t> message = Decode<checkpoint_t>(data, &problem);
  SessionSnapshot snapshot;
  if (message) problem = ReadCheckpoint(*message, &snapshot, &designs_);
  if (!problem.empty()) {  // a damaged one: the last sound one stands, and the message says so
    ++point_.checkpoints_refused;
    point_.checkpoint_refusal = message ? problem : "a CHECKPOINT that does not decode: " + problem;
    return;
  }
  point_.checkpoints_refused = 0;
  point_.checkpoint_refusal.clear();
  point_.snapshot = std::move(snapshot);
  point_.step = point_.last_step = message->step;
  point_.sim_time = point_.last_time = message->sim_time;
  point_.state_hash = uint64_t(message->state_hash);
  point_.reason = message->reason;
  point_.commands_lost = 0;
}

// A command's step, with the time it stands for at the checkpoint's step length.
void ResumeSearch::Applied(const std::vector<uint8_t>& data) {
  const std::optional<applied_command_t> command = Decode<applied_command_t>(data);
  if (!found() || !command) return;
  ++point_.commands_lost;
  if (command->step > point_.last_step) {
    point_.last_time += double(command->step - point_.last_step) * point_.snapshot.scene.sim.dt;
    point_.last_step = command->step;
  }
}

void ResumeSearch::Progress(int64_t step, double sim_time) {
  if (!found() || step <= point_.last_step) return;
  point_.last_step = step;
  point_.last_time = sim_time;
}

/// "; 2[ later] CHECKPOINT(s) refused, the last: checkpoint at step 7500: substeps: ..."; "" if none was.
std::string Refused(const ResumePoint& point, const std::string& later) {
  if (point.checkpoints_refused == 0) return "";
  return "; " + std::to_string(point.checkpoints_refused) + later +
         " CHECKPOINT(s) refused, the last: " + point.checkpoint_refusal;
}

}  // namespace

ResumePoint FindResumePoint(const std::string& path, const std::string& prefix) {
  ResumePoint point;
  std::unique_ptr<EventLogReader> reader;
  try {
    reader = std::make_unique<EventLogReader>(path);
  } catch (const std::exception& error) {
    point.error = error.what();
    return point;
  }
  const Channels channels(prefix);
  const auto wanted = [&channels](const std::string& channel) {
    return channel == channels.checkpoint || channel == channels.applied || channel == channels.status ||
           channel == channels.state || channel == channels.design_file;
  };
  ResumeSearch search(&point);
  LogEvent event;
  while (reader->Next(&event, wanted)) {
    if (event.channel == channels.checkpoint) {
      search.Checkpoint(event.data);
    } else if (event.channel == channels.applied) {
      search.Applied(event.data);
    } else if (event.channel == channels.design_file) {
      search.DesignPiece(event.data);
    } else if (event.channel == channels.status) {
      if (const std::optional<status_t> status = Decode<status_t>(event.data))
        search.Progress(status->step, status->sim_time);
    } else if (event.channel == channels.state) {
      if (const std::optional<state_t> state = Decode<state_t>(event.data))
        search.Progress(state->step, state->sim_time);
    }
  }
  if (reader->end() != EventLogReader::End::kClean) point.log_end = reader->problem();
  if (!search.found()) {
    // Where the reader stopped early ("LOG: at byte 0, event 0: not an LCM event log (...)"), and
    // the checkpoints refused, say more than that none was found.
    const std::string none = "no whole CHECKPOINT on " + channels.checkpoint;
    point.error = (point.log_end.empty() ? path + ": " + none : point.log_end + "; " + none + " before it") +
                  " to resume from (a log of flagd --record-inputs, or a recording of the bus, with the "
                  "same --prefix)" +
                  Refused(point, "");
  }
  return point;
}

std::string DescribeResume(const ResumePoint& point) {
  char text[512];
  std::snprintf(text, sizeof(text),
                "the %s checkpoint at step %lld (t = %.3f s); after it the log goes on to step %lld "
                "(t = %.3f s): %.3f simulated seconds and %lld command(s) are lost",
                point.reason.c_str(), static_cast<long long>(point.step), point.sim_time,
                static_cast<long long>(point.last_step), point.last_time, point.lost_seconds(),
                static_cast<long long>(point.commands_lost));
  std::string description = text + Refused(point, " later");
  if (!point.log_end.empty()) description += " (the log stops early: " + point.log_end + ")";
  return description;
}

}  // namespace flagsim
