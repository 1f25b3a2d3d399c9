// Recording channels to an LCM event log, the format lcm-logger writes and lcm-logplayer reads,
// through EventLogWriter: each event reaches the file whole as it arrives, the file is synced
// once a second, and a write that fails (a full disk) ends the log at its last whole event.
#pragma once

#include <cstdint>
#include <string>

#include "messages/bus.hpp"
#include "messages/event_log_writer.hpp"

namespace flagsim {

class LogRecorder {
 public:
  /// Opens `path` for writing (throws std::runtime_error naming it if it cannot) and records
  /// every message on channels matching `channel_regex` while the bus is handled, until it is
  /// destroyed (which closes the log).
  LogRecorder(Bus& bus, const std::string& channel_regex, const std::string& path);
  ~LogRecorder();
  LogRecorder(const LogRecorder&) = delete;
  LogRecorder& operator=(const LogRecorder&) = delete;

  int64_t events() const { return log_.events(); }
  uint64_t bytes() const { return log_.bytes(); }  ///< of the file: its whole events
  /// True once a write has failed (a full disk): the caller stops and says so, with error().
  bool failed() const { return log_.failed(); }
  /// What ended the log, what it holds and that it is whole (EventLogWriter::error); "" if not.
  const std::string& error() const { return log_.error(); }

 private:
  void Write(const std::string& channel, const uint8_t* data, size_t size);

  Bus& bus_;
  EventLogWriter log_;
  size_t subscription_ = 0;
};

}  // namespace flagsim
