// Recording channels to an LCM event log, the format lcm-logger writes and lcm-logplayer reads.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "messages/bus.hpp"

namespace lcm {
class LogFile;
}

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

  int64_t events() const { return events_; }
  uint64_t bytes() const { return bytes_; }
  /// True once a write has failed (a full disk): the caller stops and says so.
  bool failed() const { return failed_; }

 private:
  void Write(const std::string& channel, const uint8_t* data, size_t size);

  Bus& bus_;
  size_t subscription_ = 0;
  std::unique_ptr<lcm::LogFile> log_;
  int64_t events_ = 0;
  uint64_t bytes_ = 0;
  bool failed_ = false;
};

}  // namespace flagsim
