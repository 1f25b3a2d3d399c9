// The replay stream: what a session needs to be stepped again bit for bit, published beside
// the others so that any recording of the bus (flagctl record, lcm-logger) carries it.
//
//   CHECKPOINT  the session at a clean point (Session::CleanSnapshot): at the start (step 0),
//               every kCheckpointSteps steps, at each keyframe request, and at the end
//   APPLIED     each command as it came, with the step at whose start it took effect, in the
//               order applied; a keyframe request appears as REFRESH, since it makes a clean
//               point (which replay must make too)
//
// Clean points change the steps that follow in their last bits (the integrators forget what they
// carry), so they are part of a session's history: periodic ones fall on step numbers alone and
// requested ones are journaled, and replay (replay.hpp) makes each at the same boundary, in the
// same order with the commands there.
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

  /// Whether a periodic clean point falls at the boundary before step `step` (0 included).
  static bool PeriodicCheckpointAt(int64_t step) { return step % kCheckpointSteps == 0; }

  /// Publishes to `publisher`; with none it still makes the clean points, so that a session's
  /// steps do not depend on whether anyone records it.
  Journal(Publisher* publisher, const Channels& channels) : publisher_(publisher), channels_(channels) {}

  /// At every step boundary, the first included: the periodic clean point and its CHECKPOINT
  /// when one falls here.
  void AtBoundary(Session* session, int64_t utime);
  /// A keyframe request (REFRESH, request id `request`): a clean point now, journaled, and its
  /// CHECKPOINT.
  void Refresh(Session* session, int64_t request, int64_t utime);
  /// The session's end (the server stopping): its last CHECKPOINT, so that a replay of a log
  /// that runs to the end checks the end too.
  void End(Session* session, int64_t utime);
  /// A command `session` took at its current step: `channel` with the prefix, `data` as it came.
  void Applied(const Session& session, const std::string& channel, const uint8_t* data, size_t size,
               int64_t utime);

 private:
  void PublishCheckpoint(Session* session, const std::string& reason, int64_t utime);

  Publisher* publisher_;
  const Channels& channels_;
};

}  // namespace flagsim
