// Fuzz target: flagd replay's reading of a log (server/service/replay.hpp): the first whole
// CHECKPOINT read back into a session (checkpoint_codec.hpp), then APPLIED commands applied at
// their steps and STATE and CHECKPOINT hashes compared, on one thread. The input is the log
// file.
#include <cstddef>
#include <cstdint>

#include "server/service/replay.hpp"
#include "tests/fuzz/command_server.hpp"
#include "tests/fuzz/scratch_file.hpp"

using namespace flagsim;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const bool quiet = (fuzz::QuietLogs(), true);
  (void)quiet;
  static fuzz::ScratchFile file("replay_log");
  ReplayOptions options;
  options.threads = 1;
  Replay(file.Hold(data, size), options);
  return 0;
}
