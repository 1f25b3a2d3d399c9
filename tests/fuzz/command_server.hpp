// The server's side of the command channels as flagd wires it (server/service/server.hpp),
// without the loop's clock and frames: a session, the intake with its journal and its ear for
// other servers, on a bus. Targets step it when their input says so.
//
// It also checks what the server publishes, as its readers will take it:
//   ACK, APPLIED, CHECKPOINT   each passes the server's own checked decode
//   CHECKPOINT                 reads back (ReadCheckpoint): replay resumes from any of them
//   DESIGN_FILE                makes a whole design file: what replay shows a design from
//   APPLIED                    applied to a second session at the same step, it is accepted,
//                              and that session ends with the same state hash: what flagd
//                              replay does with a recording
// A failure aborts with what went wrong, which libFuzzer reports as a crash.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "messages/bus.hpp"
#include "messages/channels.hpp"
#include "messages/command_key.hpp"
#include "server/scene/scene.hpp"
#include "server/service/command_intake.hpp"
#include "server/service/journal.hpp"
#include "server/service/server_presence.hpp"
#include "server/service/server_stats.hpp"
#include "server/service/session.hpp"

namespace flagsim::fuzz {

/// A flag small enough that a step costs microseconds, on one thread, with small frames.
Scene SmallScene();

/// Logs nothing (a fuzzer's millions of rejected commands would flood stderr), unless
/// FLAGSIM_FUZZ_LOG is set: then the server logs as flagd does, to see what an input did.
void QuietLogs();

/// Aborts with `what` (and `detail`) when `ok` is false.
void Require(bool ok, const std::string& what, const std::string& detail = "");

class CommandServer {
 public:
  CommandServer(Bus& bus, const Channels& channels, std::vector<CommandKey> keys = {});

  /// Handles what waits on the bus, then what the server's loop does after it: a keyframe
  /// request gets its CHECKPOINT (Server::PublishDue).
  void HandleAll();
  /// One step, and what the loop does after it: the settled commands' ACKs, the journal's boundary.
  void Step();
  /// The end of the session: the ACKs still settling go out; the replayed session must agree.
  void Finish();

  const Session& session() const { return session_; }
  const ServerStats& stats() const { return stats_; }
  /// Whether an accepted command changed the parameters (PARAMS is due), once.
  bool TakeParamsChanged() { return intake_.TakeParamsChanged(); }

 private:
  void CheckAck(const uint8_t* data, size_t size);
  void CheckCheckpoint(const uint8_t* data, size_t size);
  void Replay(const uint8_t* data, size_t size);

  Bus& bus_;
  Session session_;
  ServerStats stats_;
  ServerPresence presence_;
  Journal journal_;
  CommandIntake intake_;
  Session replayed_;       ///< steps with the session, taking only what APPLIED says
  DesignLibrary designs_;  ///< the design files published on DESIGN_FILE, for the replay
};

}  // namespace flagsim::fuzz
