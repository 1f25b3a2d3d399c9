// flagd's main loop, a pipeline of three threads over one worker pool:
//
//   loop:  commands      bus.Handle: decode, validate, apply, ACK (between steps)
//          step          real time: as many dt steps as the clock allows (an accumulator
//                        filled at time_scale simulated seconds per wall second); paused
//                        (TIME): only the steps a TIME step owes; --fast: steps back to back
//          publish       STATE every 1/state_rate of simulated time (BoundarySchedule: at the
//                        steps a render publishes it), at once on REFRESH, and where steps
//                        taken by hand (TIME step) left a paused flag; PARAMS and
//                        TIMELINE each second, after a change and on REFRESH; STATUS each
//                        second, and the last second's again on REFRESH
//          frame         every 1/frame_rate of simulated time (BoundarySchedule): a copy of
//                        what the frame shows goes to the frame stage, and the loop steps on;
//                        paused or at a time_scale other than 1, every 1/frame_rate of the
//                        clock instead, so camera moves and parameter changes show at once
//          wait          on the bus until the next step or publication is due
//   frame stage          draws the copy, picks and compresses the changed tiles (frame_stage.hpp)
//   paced publisher      sends them no faster than the receivers keep up (paced_publisher.hpp)
//
// A frame due while the last is still in the stage or being sent is skipped, never queued; a
// keyframe asked for by REFRESH waits for the stage instead, and goes next. Keyframe requests
// (each a CHECKPOINT, a full STATE and a keyframe) are answered at most kKeyframesPerSecond
// times a second: one that comes sooner waits for its turn, coalesced with any after it.
//
// The loop reads time from an injected clock: tests drive it with a simulated one.
#pragma once

#include <atomic>
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "flagsim/status_t.hpp"
#include "messages/bus.hpp"
#include "messages/channels.hpp"
#include "messages/command_key.hpp"
#include "messages/utime.hpp"
#include "server/scene/scene.hpp"
#include "server/service/boundary_schedule.hpp"
#include "server/service/command_intake.hpp"
#include "server/service/frame_stage.hpp"
#include "server/service/inputs_log.hpp"
#include "server/service/journal.hpp"
#include "server/service/model_governor.hpp"
#include "server/service/paced_publisher.hpp"
#include "server/service/server_presence.hpp"
#include "server/service/server_stats.hpp"
#include "server/service/session.hpp"

namespace flagsim {

struct ServerOptions {
  bool fast = false;       ///< step as fast as possible instead of in real time
  double duration = 0;     ///< s of simulated time to run from where it starts, 0 = until stopped
  std::string inputs_log;  ///< if set, the journal (and STATUS) also goes into this LCM log (inputs_log.hpp)
  std::function<double()> clock = MonotonicSeconds;  ///< s, monotonic: the loop's time
  std::vector<CommandKey> command_keys;  ///< if any, commands must be signed with one (--key-file)
};

class Server {
 public:
  /// A new session of `scene`. Throws std::runtime_error naming the file if options.inputs_log
  /// cannot be written.
  Server(Bus& bus, const Channels& channels, const Scene& scene, const ServerOptions& options);
  /// A session resumed from a checkpoint (resume_point.hpp): it steps on from there as the
  /// session it was taken from would have, and its journal starts with a "resume" CHECKPOINT.
  Server(Bus& bus, const Channels& channels, const SessionSnapshot& resumed, const ServerOptions& options);

  /// Runs until `stop` becomes true or the duration is reached; then the end CHECKPOINT (and
  /// closes the inputs log), the last STATE and STATUS.
  void Run(const std::atomic<bool>& stop);

  /// One pass of the loop at `now` (s, on the clock): handle waiting commands, step what is due,
  /// publish what is due, hand a frame to the stage if one is due. Returns seconds until
  /// something is due next.
  double Tick(double now);

  /// Waits until the frame stage has sent the frame in hand to the paced publisher, and the
  /// publisher has sent it on.
  void DrainFrames();

  const Session& session() const { return session_; }
  const ServerStats& stats() const { return stats_; }
  const ServerPresence& presence() const { return presence_; }
  /// Whether and how commands are authenticated, as STATUS says it.
  std::string authentication() const { return intake_.Authentication(); }

  static constexpr double kMaxCatchUp = 0.1;  ///< s of wall time a late loop may step to catch up
  static constexpr double kTablesPerSecond = 10;  ///< most answers to tables-only REFRESH questions
  static constexpr double kKeyframesPerSecond = 10;  ///< most answers to keyframe REFRESH requests

 private:
  /// What the session starts from: a scene, or a checkpoint's snapshot (then `resumed`).
  struct Start {
    const Scene* scene = nullptr;
    const SessionSnapshot* resumed = nullptr;
  };
  Server(Bus& bus, const Channels& channels, Start start, const ServerOptions& options);
  bool Ended() const;  ///< the duration has run
  /// Whether frames follow the clock rather than simulated time: paused, or not at real time.
  bool FramesOnTheClock() const;
  void StepDue(double now);
  void AfterStep();
  void AtBoundary();
  void SwitchModel(const model::ModelDecision& decision);
  void PublishDue(double now);
  int64_t TakeKeyframeRequest(double now);
  bool KeyframeDue(double now) const;
  double UntilKeyframeDue(double now) const;
  void PublishState();
  void PublishParams();
  void PublishTimeline();
  void PublishStatus(double now);
  void FrameDue();
  void PublishFrame(const EncodedFrame& frame);

  Bus& bus_;
  const Channels& channels_;
  ServerOptions options_;
  Session session_;
  const bool resumed_;       ///< from a checkpoint: the journal's first is a "resume" one
  const double start_time_;  ///< s, simulated: where the session starts (the duration counts from it)
  ServerStats stats_;
  ServerPresence presence_;            ///< this server's id, and the others heard on the prefix
  std::unique_ptr<InputsLog> inputs_;  ///< null unless recording its inputs
  Journal journal_;
  ModelGovernor governor_;
  CommandIntake intake_;
  PacedPublisher paced_;
  FrameStage frames_;  ///< after paced_: it publishes through it, so it must stop first

  double start_wall_ = -1;  ///< s, monotonic, first Tick
  double accumulator_ = 0;  ///< s of wall time owed to the simulation
  double last_tick_ = -1;
  BoundarySchedule schedule_;  ///< STATE and frames, on simulated time
  SimCadence wall_frames_;     ///< frames on the clock, while it does not run at real time
  bool frame_due_ = false;
  int64_t keyframe_request_ = -1;     ///< a REFRESH to answer with the next frame; -1: none
  int64_t keyframe_asked_ = -1;       ///< a REFRESH waiting for its turn (kKeyframesPerSecond); -1: none
  double keyframe_answered_ = -INFINITY;  ///< s on the clock: when a keyframe request was last taken
  bool integrator_replaced_ = false;  ///< by the guard: PARAMS is due
  int64_t state_published_at_ = -1;   ///< the step of the last STATE
  bool drawn_asleep_ = false;         ///< the last frame was drawn with the flag asleep
  int64_t drawn_revision_ = -1;       ///< the session's revision when it was drawn
  double next_second_ = 0;            ///< s, monotonic, when PARAMS and STATUS are next due
  double window_sim_start_ = 0;       ///< simulated time at the last STATUS
  double window_wall_start_ = 0;      ///< wall time at the last STATUS
  uint64_t window_bytes_start_ = 0;
  std::optional<status_t> last_status_;  ///< the last second's report, published again on REFRESH
  bool tables_asked_ = false;            ///< a tables-only REFRESH waits for its answer
  double tables_answered_ = -INFINITY;   ///< s on the clock: when tables last went out for a question
};

}  // namespace flagsim
