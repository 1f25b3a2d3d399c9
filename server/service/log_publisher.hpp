// What flagd would publish, written into an LCM event log (lcm-logger's format) instead of onto
// the bus: the publisher of a render. Events are stamped on simulated time, so lcm-logplayer
// plays the log back at the pace the session ran:
//
//   Publish   now: stamped start + simulated time (STATE, PARAMS)
//   Enqueue   paced: stamped when PublishPacing would let it leave a live server, counted on
//             simulated time from now (tiles, FRAME), and written once the clock gets there, so
//             that it falls between the STATE messages as it would live
//
// The file is written by EventLogWriter: each event whole as it is written, synced once a
// second, and ended at its last whole event by a write that fails (a full disk).
#pragma once

#include <cstdint>
#include <deque>
#include <memory>
#include <string>
#include <vector>

#include "messages/event_log_writer.hpp"
#include "messages/publisher.hpp"
#include "server/service/publish_pacing.hpp"

namespace flagsim {

class LogPublisher final : public Publisher {
 public:
  /// Opens `path` for writing; `start_utime` (us since the Unix epoch) is simulated time 0.
  /// Throws std::runtime_error naming the file if it cannot be written.
  LogPublisher(const std::string& path, int64_t start_utime);
  ~LogPublisher() override;  ///< closes the file; call Close() first to keep paced messages
  LogPublisher(const LogPublisher&) = delete;
  LogPublisher& operator=(const LogPublisher&) = delete;

  /// Moves the clock to `time` (s, simulated, never backwards): paced messages due by then
  /// are written. Throws std::runtime_error if a write fails (a full disk), saying what the log
  /// holds (EventLogWriter::error).
  void AdvanceTo(double time);
  /// us since the Unix epoch at simulated time `time`: what events and messages are stamped.
  int64_t UtimeAt(double time) const;
  int64_t utime() const { return UtimeAt(time_); }

  using Publisher::Publish;
  /// Writes one event stamped now. Throws std::runtime_error if the write fails.
  void Publish(const std::string& channel, const uint8_t* data, size_t size) override;
  /// Queues a message to go out paced, from now on.
  void Enqueue(const std::string& channel, std::vector<uint8_t> bytes);

  /// Writes what is still paced, syncs and closes the file. Throws std::runtime_error on failure.
  void Close();

  const std::string& path() const { return path_; }
  int64_t events() const { return log_.events(); }
  uint64_t bytes() const { return log_.bytes(); }  ///< of the file so far

 private:
  struct Paced {
    double departure;  ///< s, simulated
    std::string channel;
    std::vector<uint8_t> bytes;
  };
  void Write(double time, const std::string& channel, const uint8_t* data, size_t size);

  std::string path_;
  EventLogWriter log_;
  int64_t start_utime_;
  double time_ = 0;  ///< s, simulated: the clock
  PublishPacing pacing_;
  std::deque<Paced> paced_;  ///< in departure order
};

}  // namespace flagsim
