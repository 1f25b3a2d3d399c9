// flagd replay: a recorded session stepped again from its log, every recorded state hash checked
// bit for bit.
//
//   resume     from the log's first whole CHECKPOINT (a session at a step boundary)
//   then, event by event in the log's order, first stepping on to the event's step:
//     APPLIED     apply the command
//     STATE       check its state hash against the replayed session's
//     CHECKPOINT  check its state hash too
//   stop at the first difference, at a log cut short, or where a new session starts.
// The thread count may differ from the recording's: the steps do not depend on it.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

namespace flagsim {

struct ReplayOptions {
  std::string prefix = "FLAGSIM_";  ///< the recorded server's channel prefix
  int threads = 0;                  ///< worker threads; 0: as recorded
};

struct ReplayReport {
  std::string error;           ///< "" or why nothing could be replayed (no checkpoint, unreadable log)
  int64_t first_step = -1;     ///< the checkpoint resumed from
  std::string first_reason;    ///< its reason: start, refresh, periodic, end, resume
  uint64_t first_hash = 0;     ///< its state hash
  int64_t last_checkpoint_step = -1;  ///< the last checkpoint whose hash was checked (equal or not)
  uint64_t last_checkpoint_hash = 0;  ///< its recorded state hash
  int64_t last_step = -1;      ///< the last step replayed to
  int threads = 0;             ///< replayed on
  int64_t commands = 0;        ///< APPLIED commands applied, auto's decisions apart
  int64_t model_switches = 0;  ///< APPLIED decisions of auto (MODEL) applied
  int64_t states_checked = 0;  ///< STATE hashes compared
  int64_t checkpoints_checked = 0;
  int64_t skipped = 0;  ///< hashes of steps before where the replay stood (not comparable)
  /// The first difference: "" if none, else what differed ("state hash at step 812: recorded
  /// 1a2b..., replayed 3c4d...", or a command the replay rejected with its reason).
  std::string divergence;
  int64_t divergence_step = -1;
  std::string
      log_end;  ///< "" for a whole log, else how it ended (cut short, damaged) or where a new session began

  bool ok() const { return error.empty() && divergence.empty(); }
};

/// Replays the session recorded in the LCM log at `path`. `progress(fraction of the file read)`
/// is called now and then if given.
ReplayReport Replay(const std::string& path, const ReplayOptions& options,
                    const std::function<void(double)>& progress = nullptr);

}  // namespace flagsim
