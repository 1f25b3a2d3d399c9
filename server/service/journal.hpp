// The replay stream: what a session needs to be stepped again bit for bit, published beside
// the others so that any recording of the bus (flagctl record, lcm-logger) carries it.
//
//   CHECKPOINT  the session at a step boundary (Session::Snapshot): at the start (step 0, or
//               where a resumed session starts), every kCheckpointSteps steps, at each keyframe
//               request, and at the end
//   APPLIED     each command that changed the session, as it came, with the step at whose
//               start it took effect, in the order applied
//   DESIGN_FILE a person's image (design_piece_t pieces) when it comes into force, before its
//               APPLIED, and again before each start, refresh and resume CHECKPOINT taken while
//               the scene or the scene it started from shows one, so that a replay from there
//               has it
//
// A checkpoint is a pure read (it carries what the integrator, the guard and the sleep watch
// carry between steps), so taking one changes nothing: replay (replay.hpp) resumes from any of
// them and needs only the commands.
#pragma once

#include <cstdint>
#include <string>

#include "messages/channels.hpp"
#include "messages/publisher.hpp"
#include "server/service/session.hpp"

namespace flagsim {

class Journal {
 public:
  static constexpr int64_t kCheckpointSteps = 2500;  ///< 5 s at the default 2 ms step

  /// Whether a periodic CHECKPOINT falls at the boundary before step `step` (0 included).
  static bool PeriodicCheckpointAt(int64_t step) { return step % kCheckpointSteps == 0; }

  /// Publishes to `publisher`; with none, nothing.
  Journal(Publisher* publisher, const Channels& channels) : publisher_(publisher), channels_(channels) {}

  /// At every step boundary, the first included: the periodic CHECKPOINT when one falls here
  /// (unless the session was resumed here, which has its checkpoint already).
  void AtBoundary(const Session& session, int64_t utime);
  /// A session resumed from a checkpoint (flagd --resume), before its first boundary: a
  /// "resume" CHECKPOINT, where a replay of what follows starts.
  void Resumed(const Session& session, int64_t utime);
  /// A keyframe request: a CHECKPOINT now, so that a recording that starts with a viewer's
  /// request can be replayed from there.
  void Refresh(const Session& session, int64_t utime);
  /// The session's end (the server stopping): its last CHECKPOINT, so that a replay of a log
  /// that runs to the end checks the end too.
  void End(const Session& session, int64_t utime);
  /// Who sent a command: its client id, and the key that signed it ("" unsigned).
  struct Sender {
    std::string client_id;
    std::string key_id;
  };
  /// A design file that came into force, sent by `client_id`: its pieces on DESIGN_FILE.
  void DesignFile(const flagsim::DesignFile& file, const std::string& client_id, int64_t utime);
  /// A command `session` took at its current step: `channel` with the prefix, `data` as it came.
  void Applied(const Session& session, const std::string& channel, const uint8_t* data, size_t size,
               const Sender& sender, int64_t utime);

 private:
  void PublishCheckpoint(const Session& session, const std::string& reason, int64_t utime);

  Publisher* publisher_;
  const Channels& channels_;
  int64_t resumed_step_ = -1;  ///< the step a resumed session started at; -1: none
};

}  // namespace flagsim
