// Fuzz target: the checkpoint codec (server/service/checkpoint_codec.hpp) as replay uses it. The
// input is a CHECKPOINT message: checked decode, then ReadCheckpoint. A checkpoint it accepts
// must make a session that steps, and whose own checkpoint, written after a step, reads back:
// what the codec lets in, it can write out again.
#include <cstddef>
#include <cstdint>
#include <string>

#include "flagsim/checkpoint_t.hpp"
#include "messages/checked_decode.hpp"
#include "server/service/checkpoint_codec.hpp"
#include "server/service/session.hpp"
#include "tests/fuzz/command_server.hpp"

using namespace flagsim;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const bool quiet = (fuzz::QuietLogs(), true);
  (void)quiet;
  std::string error;
  const std::optional<checkpoint_t> message =
      wire::CheckedDecode<checkpoint_t>(data, size, 256 << 20, &error);
  if (!message) return 0;
  SessionSnapshot snapshot;
  if (!ReadCheckpoint(*message, &snapshot).empty()) return 0;
  snapshot.scene.sim.threads = snapshot.simulation.params.threads = 1;
  Session session(snapshot);
  session.Step();
  const checkpoint_t again = MakeCheckpointMessage(session.Snapshot(), "periodic", message->utime);
  SessionSnapshot reread;
  const std::string problem = ReadCheckpoint(again, &reread);
  fuzz::Require(problem.empty(), "a checkpoint written from an accepted one does not read back", problem);
  return 0;
}
