// Where a server killed mid-session starts again (`flagd --resume LOG`): the last whole
// CHECKPOINT in its own record (--record-inputs; any log with checkpoints will do), and what the
// log holds after it, which the resumed session does not have.
//
//   log, event by event (to its last whole one) =>
//     CHECKPOINT  read (checkpoint_codec.hpp); a sound one becomes the resume point, and what
//                 was counted after the last is forgotten; one that is not is counted and its
//                 refusal kept, for the message
//     APPLIED     a command after the resume point: lost
//     DESIGN_FILE pieces of a person's image, which a checkpoint showing it needs
//     STATUS      (once a second in an inputs log), STATE, APPLIED: how far the server had got,
//                 in steps and simulated seconds
//
// A power loss takes at most the last second of the log (EventLogWriter), so "how far it had got"
// is known to about a second; a process killed outright loses nothing the log was given.
#pragma once

#include <cstdint>
#include <string>

#include "server/service/session.hpp"

namespace flagsim {

struct ResumePoint {
  std::string error;  ///< "" or why there is nothing to resume from (no sound checkpoint, no log)

  SessionSnapshot snapshot;  ///< the session at the checkpoint
  int64_t step = -1;         ///< the checkpoint's step
  double sim_time = 0;       ///< s, simulated, there
  uint64_t state_hash = 0;   ///< as recorded in the checkpoint
  std::string reason;        ///< why it was taken: start, periodic, refresh, end, resume

  int64_t commands_lost = 0;  ///< APPLIED commands after the checkpoint
  int64_t last_step = -1;     ///< the furthest step the log speaks of
  double last_time = 0;       ///< s, simulated, there
  std::string log_end;        ///< "" for a log that ends between events, else where it stops
  /// CHECKPOINTs after the resume point (in the whole log, when there is none) that did not
  /// decode or read back, and why the last did not
  int64_t checkpoints_refused = 0;
  std::string checkpoint_refusal;

  double lost_seconds() const { return last_time - sim_time; }  ///< simulated, after the checkpoint
};

/// Reads the log at `path`, on the channels of `prefix`.
ResumePoint FindResumePoint(const std::string& path, const std::string& prefix);

/// "the periodic checkpoint at step 5000 (t = 10.000 s); after it the log goes on to step 5867
/// (t = 11.734 s): 1.734 simulated seconds and 2 commands are lost", the checkpoints after it
/// that were refused, and where the log stops early if it does.
std::string DescribeResume(const ResumePoint& point);

}  // namespace flagsim
