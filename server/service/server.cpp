#include "server/service/server.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "messages/utime.hpp"
#include "server/service/command_apply.hpp"
#include "server/service/message_builders.hpp"

namespace flagsim {
namespace {

constexpr double kFastBatch = 0.005;  ///< s of the clock stepped back to back in --fast mode
/// s of the clock a loop that is behind steps before it turns to the publications again; a
/// keyframe request, looked for after every step, ends the batch at once.
constexpr double kSteppingBatch = 0.01;
constexpr double kMaxWait = 0.05;        ///< s, the longest the loop sleeps on the bus
constexpr double kKeyframeWait = 0.001;  ///< s, the loop's sleep while a keyframe waits for the stage

}  // namespace

Server::Server(Bus& bus, const Channels& channels, const Scene& scene, const ServerOptions& options)
    : Server(bus, channels, Start{&scene, nullptr}, options) {}

Server::Server(Bus& bus, const Channels& channels, const SessionSnapshot& resumed,
               const ServerOptions& options)
    : Server(bus, channels, Start{nullptr, &resumed}, options) {}

// The inputs log's events are stamped on simulated time, counted from its start (time 0).
Server::Server(Bus& bus, const Channels& channels, Start start, const ServerOptions& options)
    : bus_(bus),
      channels_(channels),
      options_(options),
      session_(start.resumed ? Session(*start.resumed) : Session(*start.scene)),
      resumed_(start.resumed != nullptr),
      start_time_(session_.simulation().state().time),
      // An undecodable STATUS is counted and logged as undecodable commands are (the lambda runs
      // only once the bus is handled, after intake_ is made).
      presence_(
          bus, channels, options.clock,
          [this](const std::string& channel, const std::string& reason) { intake_.Drop(channel, reason); }),
      inputs_(options.inputs_log.empty()
                  ? nullptr
                  : std::make_unique<InputsLog>(bus, options.inputs_log,
                                                UnixMicros() - std::llround(start_time_ * 1e6))),
      journal_(inputs_ ? static_cast<Publisher*>(inputs_.get()) : &bus, channels),
      intake_(bus, channels, session_, stats_, options.command_keys, options.clock),
      paced_(bus),
      frames_([this](const EncodedFrame& frame) { PublishFrame(frame); }) {
  intake_.SetJournal(&journal_);
  intake_.SetPresence(&presence_);
}

void Server::Run(const std::atomic<bool>& stop) {
  while (!stop.load()) {
    const double wait = Tick(options_.clock());
    if (Ended()) break;
    bus_.Handle(static_cast<int>(std::ceil(wait * 1000)));
  }
  intake_.FlushPending();
  frames_.Stop();  // the last frame out, and the drawing's memory freed before the checkpoint
  journal_.End(session_, UnixMicros());
  if (inputs_) inputs_->Close();
  PublishState();  // the last word: where the flag stopped
  PublishStatus(options_.clock());
}

void Server::DrainFrames() {
  frames_.Drain();
  paced_.WaitUntilSent();
}

bool Server::Ended() const {
  return options_.duration > 0 && session_.simulation().state().time >= start_time_ + options_.duration;
}

double Server::Tick(double now) {
  if (start_wall_ < 0) {
    start_wall_ = last_tick_ = next_second_ = window_wall_start_ = now;
    window_sim_start_ = session_.simulation().state().time;
    window_bytes_start_ = bus_.bytes_published();
    if (resumed_) journal_.Resumed(session_, UnixMicros());
    AtBoundary();  // the session's first checkpoint, STATE and frame
  }
  bus_.HandleAll();
  // Held still, no step comes to settle a command under: its answer goes out now.
  if (!session_.Runs()) intake_.FlushPending();
  StepDue(now);
  // Held still after steps taken by hand: the state they reached goes out, wherever it fell.
  if (!session_.Runs() && state_published_at_ != session_.simulation().state().step) PublishState();
  PublishDue(now);
  const double frame_rate = session_.scene().service.frame_rate;
  if (FramesOnTheClock() && wall_frames_.Due(now, frame_rate)) frame_due_ = true;
  FrameDue();
  if (options_.fast && session_.Runs()) return 0;
  // Asleep, steps only move the clock: take them in batches and let the machine rest. Paused,
  // no step is due until a command comes.
  const double scale = session_.scene().service.time_scale;
  const double until_step = session_.simulation().sleeping() || !session_.Runs()
                                ? kMaxWait
                                : (session_.scene().sim.dt - accumulator_) / scale;
  const double until_frame = FramesOnTheClock() && frame_rate > 0 ? wall_frames_.next() - now : INFINITY;
  const double longest = keyframe_request_ >= 0 ? kKeyframeWait : kMaxWait;
  const double until_due = std::min({until_step, until_frame, next_second_ - now, UntilKeyframeDue(now)});
  return std::clamp(until_due, 0.0, longest);
}

bool Server::FramesOnTheClock() const {
  return !options_.fast && (session_.paused() || session_.scene().service.time_scale != 1);
}

// Real time: the accumulator owes the simulation the clock's time since the last tick times
// time_scale, in whole steps; a loop that fell far behind drops the excess rather than
// spiralling. Paused, it owes nothing but the steps a TIME step asked for, taken back to back.
// --fast: steps for kFastBatch of the clock (at least one), then the publications get their
// turn. In real time a batch ends after kSteppingBatch of the clock, and what is still owed is
// stepped at the next tick. The bus is handled after every step: a keyframe request due ends
// the batch, and a TIME pause stops it.
void Server::StepDue(double now) {
  const double dt = session_.scene().sim.dt, scale = session_.scene().service.time_scale;
  const bool owes_time = !options_.fast && !session_.paused();
  accumulator_ = owes_time ? std::min(accumulator_ + (now - last_tick_) * scale, kMaxCatchUp * scale) : 0.0;
  last_tick_ = now;
  const double deadline = now + (options_.fast ? kFastBatch : kSteppingBatch);
  const auto due = [&] {
    if (!session_.Runs() || Ended()) return false;
    return options_.fast || session_.paused() || accumulator_ >= dt;  // paused: a step owed
  };
  while (due()) {
    const double start = options_.clock();
    integrator_replaced_ |= session_.Step();
    const double end = options_.clock();
    ++stats_.steps;
    stats_.step_seconds += end - start;
    accumulator_ -= dt;
    AfterStep();
    if (end >= deadline) break;
    // Commands take effect at the next step's start, as if the batch ended here; a keyframe
    // request whose turn has come ends it, so that its frame need not wait for the rest of the batch.
    bus_.HandleAll();
    if (KeyframeDue(end)) break;
  }
  if (options_.fast) accumulator_ = 0;
}

void Server::AfterStep() {
  intake_.AfterStep();
  AtBoundary();
}

// STATE and frames fall due on simulated time (BoundarySchedule). STATE goes out at once, and so
// does a frame to the stage (FrameDue), unless the stage or the publisher is still busy with the last.
void Server::AtBoundary() {
  if (inputs_) inputs_->AdvanceTo(session_.simulation().state().time);
  journal_.AtBoundary(session_, UnixMicros());
  if (const auto decision = governor_.AtBoundary(session_)) SwitchModel(*decision);
  const BoundaryDue due = schedule_.At(session_);
  if (due.state) PublishState();
  if (due.frame && !FramesOnTheClock()) {
    if (frame_due_) ++stats_.frames_skipped;
    frame_due_ = true;
    FrameDue();  // at its own step, not after the batch: the stage takes a copy and the loop goes on
  }
}

// decision => MODEL bytes => the session, and the journal as a command from "auto"
void Server::SwitchModel(const model::ModelDecision& decision) {
  const int64_t utime = UnixMicros();
  const model_t message = ModelMessageOf(decision, utime);
  std::vector<uint8_t> bytes(size_t(message.getEncodedSize()));
  message.encode(bytes.data(), 0, int(bytes.size()));
  ModelSwitch model;
  std::string problem = ModelSwitchOf(message, &model);
  if (problem.empty()) problem = session_.ApplyModel(model);
  if (!problem.empty()) {
    spdlog::warn("auto's decision {} was not taken: {}", model::Describe(decision), problem);
    return;
  }
  journal_.Applied(session_, channels_.model, bytes.data(), bytes.size(), {"auto", ""}, utime);
  governor_.Switched(session_);
  integrator_replaced_ = true;  // PARAMS is due
  spdlog::info("auto at step {}: {} ({})", session_.simulation().state().step, model::Describe(decision),
               model::Describe(decision.kind));
}

void Server::PublishDue(double now) {
  const int64_t request = TakeKeyframeRequest(now);
  const bool refresh = request >= 0;
  if (refresh) {
    journal_.Refresh(session_, UnixMicros());
    PublishState();
    keyframe_request_ = request;  // the latest, if several
    frame_due_ = true;            // the keyframe goes out now, not at the next frame time
  }
  // A client asking for the tables (flagctl status) has them at once, the last second's report
  // too; questions are coalesced and answered at most kTablesPerSecond times a second.
  tables_asked_ |= intake_.TakeTablesRequest();
  const bool tables = refresh || (tables_asked_ && now - tables_answered_ >= 1.0 / kTablesPerSecond);
  if (tables) {
    tables_asked_ = false;
    tables_answered_ = now;
  }
  if (intake_.TakeParamsChanged() || std::exchange(integrator_replaced_, false) || tables) PublishParams();
  if (intake_.TakeTimelineChanged() || tables) PublishTimeline();
  if (tables && last_status_) {
    last_status_->other_servers = presence_.others();  // who is on the prefix is news, not history
    bus_.Publish(channels_.status, *last_status_);
  }
  if (now >= next_second_) {
    PublishParams();
    PublishTimeline();
    PublishStatus(now);
    next_second_ = std::max(next_second_ + 1.0, now);
  }
}

// A keyframe request costs a CHECKPOINT, a full STATE and a keyframe: taken at most once per
// 1/kKeyframesPerSecond of the clock. One that comes sooner waits for that time, never dropped;
// requests that wait together are answered by one keyframe naming the latest. Returns its id,
// or -1 when none is taken now.
int64_t Server::TakeKeyframeRequest(double now) {
  const int64_t asked = intake_.TakeRefreshRequest();
  if (asked >= 0) keyframe_asked_ = asked;
  if (!KeyframeDue(now)) return -1;
  keyframe_answered_ = now;
  return std::exchange(keyframe_asked_, -1);
}

// Whether a keyframe request waits and its turn has come.
bool Server::KeyframeDue(double now) const { return UntilKeyframeDue(now) <= 0; }

// s on the clock until a waiting keyframe request may be taken (0 or less: now); infinite when
// none waits.
double Server::UntilKeyframeDue(double now) const {
  if (keyframe_asked_ < 0 && !intake_.RefreshPending()) return INFINITY;
  return keyframe_answered_ + 1.0 / kKeyframesPerSecond - now;
}

void Server::PublishState() {
  const double start = options_.clock();
  state_t state = MakeStateMessage(session_, UnixMicros());
  state.server_id = presence_.id();
  bus_.Publish(channels_.state, state);
  state_published_at_ = state.step;
  stats_.publish_seconds += options_.clock() - start;
  ++stats_.states_published;
}

// state => a copy => the frame stage. Skipped while the last frame is still in the stage or
// being sent, unless it answers a REFRESH: then it waits for them and goes next.
void Server::FrameDue() {
  if (!frame_due_) return;  // due by the frame rate, or asked for by REFRESH (even at frame_rate 0)
  // Asleep, with nothing changed since a frame drawn asleep, a new frame would be the same.
  // (Paused, frames go on at the frame rate: the stream's rolling refresh goes on with them.)
  const bool asleep = session_.simulation().sleeping();
  const bool keyframe = keyframe_request_ >= 0;
  if (asleep && drawn_asleep_ && drawn_revision_ == session_.revision() && !keyframe) {
    frame_due_ = false;
    return;
  }
  if (frames_.Busy() || paced_.queued() > 0) {
    if (!keyframe) {
      frame_due_ = false;
      ++stats_.frames_skipped;
    }
    return;
  }
  frame_due_ = false;
  frames_.Submit(FrameInput::Of(session_, UnixMicros()), session_.scene().sim.threads,
                 std::exchange(keyframe_request_, -1));
  ++stats_.frames_published;
  drawn_asleep_ = asleep;
  drawn_revision_ = session_.revision();
}

// On the stage's thread: tiles, then the manifest, to the paced publisher.
void Server::PublishFrame(const EncodedFrame& frame) {
  for (const tile_t& tile : frame.tiles) paced_.Enqueue(channels_.tile, tile);
  paced_.Enqueue(channels_.frame, frame.manifest);
}

void Server::PublishParams() {
  bus_.Publish(channels_.params, MakeParamsMessage(session_.scene(), UnixMicros()));
}

void Server::PublishTimeline() {
  bus_.Publish(channels_.timeline, MakeTimelineMessage(session_.scene().timeline,
                                                       session_.simulation().state().step, UnixMicros()));
}

void Server::PublishStatus(double now) {
  StatusWindow window;
  window.wall_seconds = now - window_wall_start_;
  window.sim_seconds = session_.simulation().state().time - window_sim_start_;
  window.bytes = double(bus_.bytes_published() - window_bytes_start_);
  window.uptime = now - start_wall_;
  const FrameStageStats drawn = frames_.TakeStats();
  stats_.render_seconds += drawn.render_seconds;
  stats_.encode_seconds += drawn.encode_seconds;
  stats_.tiles_published += drawn.tiles;
  stats_.tile_bytes += drawn.tile_bytes;
  status_t status = MakeStatusMessage(session_, stats_, window, UnixMicros());
  status.server_id = presence_.id();
  status.other_servers = presence_.others();
  status.command_authentication = intake_.Authentication();
  WriteModelStatus(session_, governor_.last(), &status);
  // Into the inputs log too: where the server stood each second, for a resume to say what it lost.
  (inputs_ ? static_cast<Publisher&>(*inputs_) : bus_).Publish(channels_.status, status);
  last_status_ = status;
  stats_.ResetWindow();
  window_wall_start_ = now;
  window_sim_start_ = session_.simulation().state().time;
  window_bytes_start_ = bus_.bytes_published();
}

}  // namespace flagsim
