#include "server/service/command_intake.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdio>

#include "common/printable_text.hpp"
#include "messages/checked_decode.hpp"
#include "messages/utime.hpp"
#include "server/scene/scene_timeline.hpp"
#include "server/service/command_apply.hpp"

namespace flagsim {
namespace {

/// "" if a client id can be answered to, else why not.
std::string CheckClientId(const std::string& client_id) {
  if (client_id.empty() || client_id.size() > CommandIntake::kMaxClientIdLength) {
    return "client_id: " + std::to_string(client_id.size()) + " characters; allowed 1 .. " +
           std::to_string(CommandIntake::kMaxClientIdLength);
  }
  for (const char c : client_id) {
    if (c < 0x21 || c > 0x7e) return "client_id: allowed printable ASCII without spaces";
  }
  return "";
}

/// Whether a command must be signed when the server has keys: all but a reader's question,
/// which changes nothing.
template <class Command>
bool NeedsSignature(const Command&) {
  return true;
}
bool NeedsSignature(const refresh_request_t& request) { return !request.tables_only; }

/// What an accepted command set: the wind, the camera, parameters by name.
struct CommandSets {
  bool wind = false;
  bool camera = false;
  std::vector<std::string> names;
};

/// A note for an accepted command that set controls a playing timeline drives: "" if it drives
/// none of them.
std::string TimelineNote(const sim::Timeline& timeline, const CommandSets& sets) {
  if (!timeline.playing()) return "";
  const sim::Controls driven = timeline.Evaluate(timeline.position());
  std::string overlap = sets.wind && driven.wind ? "the wind" : "";
  if (sets.camera && driven.camera) overlap += (overlap.empty() ? "" : ", ") + std::string("the camera");
  const std::vector<std::string>& names = sets.names;
  for (const sim::ParameterControl& parameter : driven.parameters) {
    if (std::find(names.begin(), names.end(), parameter.name) != names.end())
      overlap += (overlap.empty() ? "" : ", ") + parameter.name;
  }
  if (overlap.empty()) return "";
  return "applied, but the playing timeline sets " + overlap +
         " from the next step on (keyframe pause leaves them to commands)";
}

/// After a reset: the clock is the viewer's, and a reset leaves it; say so where it is not real time.
std::string ClockNote(const Session& session, const std::string& note) {
  std::string clock;
  if (session.paused()) clock = "the simulation stays paused (flagctl time resume)";
  const double scale = session.scene().service.time_scale;
  if (scale != 1) {
    char text[96];
    std::snprintf(text, sizeof(text), "time_scale stays %g (a reset leaves it; flagctl time scale 1)", scale);
    clock += (clock.empty() ? "" : "; ") + std::string(text);
  }
  if (clock.empty()) return note;
  return note.empty() ? clock : note + "; " + clock;
}

}  // namespace

CommandIntake::CommandIntake(Bus& bus, const Channels& channels, Session& session, ServerStats& stats,
                             std::vector<CommandKey> keys, std::function<double()> clock)
    : bus_(bus),
      channels_(channels),
      session_(session),
      stats_(stats),
      authenticator_(std::move(keys)),
      clock_(std::move(clock)) {
  Subscribe<wind_command_t>(channels.wind, &CommandIntake::ApplyWind);
  Subscribe<param_command_t>(channels.param, &CommandIntake::ApplyParams);
  Subscribe<refresh_request_t>(channels.refresh, &CommandIntake::ApplyRefresh);
  Subscribe<camera_command_t>(channels.camera, &CommandIntake::ApplyCamera);
  Subscribe<keyframe_command_t>(channels.keyframe, &CommandIntake::ApplyKeyframe);
  Subscribe<time_command_t>(channels.time, &CommandIntake::ApplyTime);
  Subscribe<design_piece_t>(channels.design, &CommandIntake::ApplyDesignPiece);
}

template <class Command>
void CommandIntake::Subscribe(const std::string& channel,
                              std::string (CommandIntake::*apply)(const Command&)) {
  subscriptions_.Subscribe(
      channel,
      [this, apply](const std::string& name, const uint8_t* data, size_t size) {
        OnMessage<Command>(name, data, size, apply);
      },
      kQueueCapacity);
}

// bytes => decode (checked) => authentic? => duplicate? => validate and apply => ACK
template <class Command>
void CommandIntake::OnMessage(const std::string& channel, const uint8_t* data, size_t size,
                              std::string (CommandIntake::*apply)(const Command&)) {
  std::string error;
  const std::optional<Command> command = wire::CheckedDecode<Command>(data, size, kMaxCommandBytes, &error);
  if (!command) return Drop(channel, error);
  const bool question = !NeedsSignature(*command);
  if (!question) {
    const CommandAuthenticator::Verdict verdict = authenticator_.Check(channel, *command, UnixMicros());
    if (verdict.refusal != CommandAuthenticator::Refusal::kNone)
      return Refuse(channel, command->client_id, command->sequence, verdict);
  }

  const auto previous = last_ack_.find(command->client_id);
  if (previous != last_ack_.end() && previous->second.sequence == command->sequence) {
    // A retry: applied once; the same answer again, or nothing yet while it settles.
    if (previous->second.utime > 0) bus_.Publish(channels_.ack, previous->second);
    return;
  }

  ack_t ack;
  ack.client_id = command->client_id;
  ack.sequence = command->sequence;
  ack.channel = channels_.Unprefixed(channel);
  ack.step = session_.simulation().state().step;
  ack.reason = CheckClientId(command->client_id);
  // A client id refused is answered and logged as printable text, cut to the length allowed.
  if (!ack.reason.empty()) ack.client_id = PrintableText(command->client_id, kMaxClientIdLength);
  const int64_t recoveries = session_.simulation().recoveries();
  note_.clear();
  design_shown_.reset();
  if (ack.reason.empty()) ack.reason = (this->*apply)(*command);
  ack.accepted = ack.reason.empty();
  if (ack.accepted) ack.reason = note_;
  if (question) return Answer(ack, recoveries);  // answered, not counted or logged as a command
  if (ack.accepted) {
    // What changes the session goes into the journal; a REFRESH changes nothing, nor does a
    // DESIGN piece until it completes its file, which goes out whole first.
    const bool changed = channel != channels_.refresh && (channel != channels_.design || design_shown_);
    if (journal_ != nullptr && design_shown_)
      journal_->DesignFile(*design_shown_, command->client_id, UnixMicros());
    if (journal_ != nullptr && changed)
      journal_->Applied(session_, channel, data, size, {command->client_id, command->key_id}, UnixMicros());
    ++stats_.commands_accepted;
    spdlog::info("{} from {} #{}: accepted at step {}", ack.channel, ack.client_id, ack.sequence, ack.step);
  } else {
    ++stats_.commands_rejected;
    spdlog::warn("{} from {} #{}: rejected: {}", ack.channel, ack.client_id, ack.sequence, ack.reason);
  }
  if (last_ack_.size() >= 1024) last_ack_.clear();  // bound the memory strangers can claim
  const bool settles = ack.accepted && (channel == channels_.wind || channel == channels_.param);
  if (settles && settling_.size() < size_t(kQueueCapacity)) {
    ack.utime = 0;  // not answered yet
    last_ack_[ack.client_id] = ack;
    settling_.push_back({ack, ack.step + kSettleSteps, recoveries});
    return;
  }
  Answer(ack, recoveries);
}

// The ACK goes out, noting any recovery since the command was applied.
void CommandIntake::Answer(ack_t ack, int64_t recoveries_before) {
  const sim::GuardEvent& event = session_.simulation().last_guard_event();
  if (ack.accepted && session_.simulation().recoveries() > recoveries_before) {
    ack.reason = (ack.reason.empty() ? "" : ack.reason + "; ") +
                 "applied; then the guard caught the flag at " + event.Describe();
    spdlog::warn("{} from {} #{}: {}", ack.channel, ack.client_id, ack.sequence, ack.reason);
  }
  Stamp(&ack);
  const auto last = last_ack_.find(ack.client_id);
  const bool newer_came = last != last_ack_.end() && last->second.sequence != ack.sequence;
  if (!ack.client_id.empty() && !newer_came) last_ack_[ack.client_id] = ack;
  bus_.Publish(channels_.ack, ack);
}

void CommandIntake::AfterStep() {
  const int64_t step = session_.simulation().state().step;
  size_t answered = 0;
  while (answered < settling_.size() && settling_[answered].due_step <= step) {
    Answer(settling_[answered].ack, settling_[answered].recoveries_before);
    ++answered;
  }
  settling_.erase(settling_.begin(), settling_.begin() + answered);
}

void CommandIntake::FlushPending() {
  for (const Settling& each : settling_) Answer(each.ack, each.recoveries_before);
  settling_.clear();
}

std::string CommandIntake::ApplyWind(const wind_command_t& command) {
  const std::string problem = session_.ApplyWind(WindOf(command));
  if (problem.empty()) note_ = TimelineNote(session_.scene().timeline, {true, false, {}});
  return problem;
}

std::string CommandIntake::ApplyParams(const param_command_t& command) {
  const ParamChange change = ParamChangeOf(command);
  const std::string problem = session_.ApplyParams(change);
  params_changed_ |= problem.empty();
  timeline_changed_ |= problem.empty() && change.reset_to_scene;  // back to the scene's timeline
  if (problem.empty()) note_ = TimelineNote(session_.scene().timeline, {false, false, command.names});
  if (problem.empty() && change.reset_to_scene) note_ = ClockNote(session_, note_);
  return problem;
}

std::string CommandIntake::ApplyRefresh(const refresh_request_t& command) {
  if (command.sequence < 0) return "sequence: " + std::to_string(command.sequence) + "; allowed 0 and up";
  if (command.tables_only) {
    tables_request_ = true;
    return "";
  }
  refresh_request_ = command.sequence;  // coalesced: requests before the next frame make one keyframe
  return "";
}

std::string CommandIntake::ApplyCamera(const camera_command_t& command) {
  const render::CameraMove move = CameraMoveOf(command);
  const std::string problem = session_.ApplyCamera(move);
  // The moves of eye, target and field of view (a timeline's camera); rotations and scaling of
  // the scene stay.
  using Move = render::CameraMove;
  const bool moves = move.operation == Move::kTranslate || move.operation == Move::kOrbit ||
                     move.operation == Move::kLookAt || move.operation == Move::kReset ||
                     move.operation == Move::kZoom || move.operation == Move::kSetEye ||
                     move.operation == Move::kSetFov || move.operation == Move::kFrame ||
                     move.operation == Move::kZoomAt;
  if (problem.empty()) note_ = TimelineNote(session_.scene().timeline, {false, moves, {}});
  return problem;
}

std::string CommandIntake::ApplyKeyframe(const keyframe_command_t& command) {
  TimelineEdit edit;
  std::string problem = TimelineEditOf(command, &edit);
  if (problem.empty()) problem = session_.ApplyTimeline(edit);
  timeline_changed_ |= problem.empty();
  return problem;
}

std::string CommandIntake::ApplyTime(const time_command_t& command) {
  TimeControl control;
  const std::string problem = TimeControlOf(command, &control);
  return problem.empty() ? session_.ApplyTime(control) : problem;
}

// piece => held => whole and matching its digest? => decoded within the limits => shown
std::string CommandIntake::ApplyDesignPiece(const design_piece_t& piece) {
  DesignAssembly::Outcome outcome = designs_.Add(piece);
  if (!outcome.problem.empty()) return outcome.problem;
  if (!outcome.whole) {
    note_ = "held " + std::to_string(outcome.held) + " of " + std::to_string(piece.total_bytes) +
            " bytes of " + piece.name;
    return "";
  }
  DesignFilePtr file;
  std::string problem = MakeDesignFile(piece.name, std::move(outcome.bytes), &file);
  if (!problem.empty()) return piece.name + ": " + problem;
  problem = session_.ApplyDesign(file);
  if (!problem.empty()) return piece.name + ": " + problem;
  design_shown_ = file;
  params_changed_ = true;
  char size[96];
  std::snprintf(size, sizeof(size), " (%d x %d px), the flag %.3g m wide", file->width, file->height,
                session_.scene().sim.width);
  note_ = "design " + file->name + size;
  return "";
}

static_assert(std::tuple_size_v<decltype(ServerStats::commands_refused)> ==
              CommandAuthenticator::kRefusalKinds);

// Counted always; answered and logged up to kRefusalAnswersPerSecond, the log naming the key and
// client but never anything secret.
void CommandIntake::Refuse(const std::string& channel, const std::string& client_id, int64_t sequence,
                           const CommandAuthenticator::Verdict& verdict) {
  ++stats_.commands_refused[static_cast<size_t>(verdict.refusal)];
  const double now = clock_();
  if (now - refusal_second_ >= 1.0) {
    if (refusals_in_second_ > kRefusalAnswersPerSecond)
      spdlog::warn("{} more command(s) refused in that second, counted but not answered",
                   refusals_in_second_ - kRefusalAnswersPerSecond);
    refusal_second_ = now;
    refusals_in_second_ = 0;
  }
  if (++refusals_in_second_ > kRefusalAnswersPerSecond) return;
  ack_t ack;
  ack.client_id = PrintableText(client_id, kMaxClientIdLength);
  ack.sequence = sequence;
  ack.channel = channels_.Unprefixed(channel);
  ack.accepted = false;
  ack.reason = verdict.reason;
  ack.step = session_.simulation().state().step;
  spdlog::warn("{} from {} #{}: refused: {}", ack.channel, ack.client_id, ack.sequence, ack.reason);
  Stamp(&ack);
  bus_.Publish(channels_.ack, ack);
}

// The answer's time, and who answers: this server's id and how many others it hears.
void CommandIntake::Stamp(ack_t* ack) const {
  ack->utime = UnixMicros();
  if (presence_ != nullptr) {
    ack->server_id = presence_->id();
    ack->other_servers = presence_->others();
  }
}

void CommandIntake::Drop(const std::string& channel, const std::string& reason) {
  ++stats_.messages_dropped;
  ++drops_since_log_;
  const double now = clock_();
  if (now - last_drop_log_ >= 1.0) {
    spdlog::warn("dropped {} undecodable message(s); latest on {}: {}", drops_since_log_, channel, reason);
    last_drop_log_ = now;
    drops_since_log_ = 0;
  }
}

}  // namespace flagsim
