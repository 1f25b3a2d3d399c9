// Counters and timings the server reports in STATUS.
#pragma once

#include <cstdint>

namespace flagsim {

struct ServerStats {
  // Since the server started.
  int64_t commands_accepted = 0;  ///< valid commands applied
  int64_t commands_rejected = 0;  ///< decoded but invalid: answered with a reason
  int64_t messages_dropped = 0;   ///< undecodable bytes on a command channel: no answer possible

  // Since the last STATUS (reset each time one is published).
  int64_t steps = 0;
  double step_seconds = 0;        ///< wall time spent stepping
  int64_t states_published = 0;
  double publish_seconds = 0;     ///< wall time spent building and publishing STATE
  int64_t frames_published = 0;

  void ResetWindow() {
    steps = 0;
    step_seconds = 0;
    states_published = 0;
    publish_seconds = 0;
    frames_published = 0;
  }
};

}  // namespace flagsim
