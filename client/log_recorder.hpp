// Recording a server's channels to an LCM event log, the format lcm-logger writes and
// lcm-logplayer reads, through EventLogWriter: each event reaches the file whole as it arrives,
// the file is synced once a second, and a write that fails (a full disk) ends the log at its
// last whole event.
//
// A log replays (flagd replay) from its first CHECKPOINT and exports from its first whole frame;
// a server sends both at once when asked (REFRESH). The recorder says when to ask: at its start,
// and again while no checkpoint has come (the request or its answer lost on the way).
#pragma once

#include <cstdint>
#include <string>

#include "messages/bus.hpp"
#include "messages/channels.hpp"
#include "messages/event_log_writer.hpp"

namespace flagsim {

class LogRecorder {
 public:
  static constexpr double kAskInterval = 1.0;  ///< s between keyframe requests while no checkpoint comes
  static constexpr int kAsks = 3;              ///< requests at most (a log playing back never answers)

  /// Opens `path` for writing (throws std::runtime_error naming it if it cannot) and records
  /// every message on `channels` while the bus is handled, until it is destroyed (which closes
  /// the log).
  LogRecorder(Bus& bus, const Channels& channels, const std::string& path);
  ~LogRecorder();
  LogRecorder(const LogRecorder&) = delete;
  LogRecorder& operator=(const LogRecorder&) = delete;

  /// Whether to send a keyframe request now (`now`: s on the caller's clock): at the first
  /// call, then every kAskInterval s while the log holds no CHECKPOINT, kAsks times in all.
  bool KeyframeRequestDue(double now);

  int64_t events() const { return log_.events(); }
  uint64_t bytes() const { return log_.bytes(); }  ///< of the file: its whole events
  int64_t checkpoints() const { return checkpoints_; }
  /// True once a write has failed (a full disk): the caller stops and says so, with error().
  bool failed() const { return log_.failed(); }
  /// What ended the log, what it holds and that it is whole (EventLogWriter::error); "" if not.
  const std::string& error() const { return log_.error(); }

 private:
  void Write(const std::string& channel, const uint8_t* data, size_t size);

  Bus& bus_;
  std::string checkpoint_channel_;
  EventLogWriter log_;
  size_t subscription_ = 0;
  int64_t checkpoints_ = 0;  ///< CHECKPOINT events written
  int asks_ = 0;             ///< keyframe requests said due
  double asked_ = 0;         ///< s, the caller's clock: when the last was
};

}  // namespace flagsim
