// Counters and timings the server reports in STATUS.
#pragma once

#include <array>
#include <cstdint>

namespace flagsim {

struct ServerStats {
  // Since the server started.
  int64_t commands_accepted = 0;  ///< valid commands applied
  int64_t commands_rejected = 0;  ///< decoded but invalid: answered with a reason
  int64_t messages_dropped = 0;   ///< undecodable bytes on a command channel or STATUS: no answer possible
  /// Commands refused by their signature, by CommandAuthenticator::Refusal (index 0 unused).
  std::array<int64_t, 6> commands_refused{};
  int64_t frames_skipped = 0;     ///< frames due but not drawn: the publisher or the loop was behind

  // Since the last STATUS (reset each time one is published).
  int64_t steps = 0;
  double step_seconds = 0;  ///< wall time spent stepping
  int64_t states_published = 0;
  double publish_seconds = 0;  ///< wall time spent building and publishing STATE
  int64_t frames_published = 0;
  double render_seconds = 0;  ///< wall time spent drawing frames
  double encode_seconds = 0;  ///< wall time spent hashing and compressing tiles
  int64_t tiles_published = 0;
  double tile_bytes = 0;  ///< compressed tile payloads

  void ResetWindow() {
    render_seconds = 0;
    encode_seconds = 0;
    tiles_published = 0;
    tile_bytes = 0;
    steps = 0;
    step_seconds = 0;
    states_published = 0;
    publish_seconds = 0;
    frames_published = 0;
  }
};

}  // namespace flagsim
