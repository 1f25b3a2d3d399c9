// flagd's own record of its inputs (`flagd --record-inputs LOG`): the journal's stream (each
// CHECKPOINT and APPLIED command, journal.hpp) goes onto the bus as always and into an LCM event
// log as well, which `flagd replay` steps again and `flagd --resume` starts again from; STATUS
// goes in too, once a second, so that a resume knows how far the server had got. The log holds
// nothing else: its checkpoints (every node's position and velocity, each 5 s of simulated
// time) make most of it, about 300 KB a minute with the default 32 x 24 flag, where a recording
// of the bus takes megabytes a second.
//
//   journal, STATUS => InputsLog::Publish => bus (always)
//                                         => log, stamped on simulated time (log_publisher.hpp)
//
// Each event reaches the file whole as it is published, and the file is synced once a second
// (EventLogWriter): a server killed outright leaves all it recorded, one that loses its power
// all but the last second. A write that fails (a full disk) ends the log at its last whole
// event, with an error logged that says so, and never the server: the bus goes on receiving
// everything.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "messages/publisher.hpp"
#include "server/service/log_publisher.hpp"

namespace flagsim {

class InputsLog final : public Publisher {
 public:
  /// Opens `path` for writing; `start_utime` (us since the Unix epoch) is simulated time 0.
  /// Throws std::runtime_error naming the file if it cannot be written.
  InputsLog(Publisher& bus, const std::string& path, int64_t start_utime);

  /// Moves the log's clock to `time` (s, simulated): what is published next is stamped then.
  void AdvanceTo(double time);

  using Publisher::Publish;
  void Publish(const std::string& channel, const uint8_t* data, size_t size) override;

  /// Flushes and closes the log; false (with an error logged) if it had failed or fails now.
  bool Close();

  const std::string& path() const { return path_; }

 private:
  void Fail(const std::string& what);

  Publisher& bus_;
  std::string path_;
  std::unique_ptr<LogPublisher> log_;  ///< null once closed or failed
  bool failed_ = false;
};

}  // namespace flagsim
