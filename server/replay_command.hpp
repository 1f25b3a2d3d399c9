// flagd replay: the command line's side of a replay (service/replay.hpp): the progress bar and
// the verdict.
#pragma once

#include "server/service/replay.hpp"

namespace flagsim {

/// Replays the log at `path` and prints what it found. Returns the exit code: 0 every recorded
/// hash equal, 1 a difference (the first is printed), 2 nothing to replay (no checkpoint, a log
/// that cannot be read).
int RunReplay(const std::string& path, const ReplayOptions& options);

}  // namespace flagsim
