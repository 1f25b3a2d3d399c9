// Writing an LCM event log (the format lcm-logger writes; event_log_reader.hpp has its layout) so
// that it survives what ends a recording badly:
//
//   a crash     each event goes to the kernel whole, in one writev(2), as it is written: a
//               process killed at any moment leaves every event before it in the file (and at
//               most one cut short, which readers stop before)
//   power loss  a thread of its own fdatasync(2)s the file once a second when something was
//               written since (and its directory once, so that the new file's name survives):
//               a machine that loses power keeps all but the last second, and the recording
//               never waits on the disk
//   full disk   a write that fails truncates the file back to the end of the last whole event
//               and ends the log, with a message that says what happened, how much it holds and
//               that it is whole; nothing is written after
//
// One thread writes (Write, Close); the counters and the error are that thread's to read.
#pragma once

#include <sys/uio.h>

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>

namespace flagsim {

class EventLogWriter {
 public:
  static constexpr double kSyncInterval = 1.0;  ///< s: the most a power loss takes

  /// Creates (or empties) `path` and starts syncing it every `sync_interval` s. Throws
  /// std::runtime_error naming the file and why if it cannot be written.
  explicit EventLogWriter(const std::string& path, double sync_interval = kSyncInterval);
  ~EventLogWriter();  ///< Close()
  EventLogWriter(const EventLogWriter&) = delete;
  EventLogWriter& operator=(const EventLogWriter&) = delete;

  /// Appends one event stamped `timestamp` (us; lcm-logger's are since the Unix epoch),
  /// numbered after the last. False if the log has ended (a write failed, now or before):
  /// then error() says why and what the file holds.
  bool Write(int64_t timestamp, const std::string& channel, const uint8_t* data, size_t size);

  /// Stops the syncing, syncs what is left and closes the file. False if the log had failed or
  /// the last sync fails. Later calls do nothing.
  bool Close();

  bool failed() const { return failed_; }
  /// "" or what ended the log: "writing run.lcmlog stopped: the disk is full (No space left on
  /// device); the log holds its first 5120 events, 7864320 bytes, every one whole".
  const std::string& error() const { return error_; }
  const std::string& path() const { return path_; }
  /// Whole events in the file, and its bytes.
  int64_t events() const { return events_; }
  uint64_t bytes() const { return bytes_; }
  /// fdatasyncs of new data so far, and the wall time spent in them.
  int64_t syncs() const { return syncs_.load(); }
  double sync_seconds() const { return sync_nanoseconds_.load() * 1e-9; }

 private:
  bool WriteAll(const iovec* parts, int count, size_t total);
  bool Fail(const std::string& what);
  void SyncEvery(double interval);
  void SyncDirectoryOnce();

  std::string path_;
  int fd_ = -1;
  int64_t events_ = 0;
  uint64_t bytes_ = 0;
  bool failed_ = false;
  std::string error_;

  // Shared with the syncing thread.
  std::atomic<uint64_t> written_{0};  ///< bytes of whole events, for the thread to sync
  std::atomic<int64_t> syncs_{0};
  std::atomic<int64_t> sync_nanoseconds_{0};
  std::atomic<int> sync_errno_{0};  ///< a failed fdatasync's errno, for Write to report
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stopping_ = false;  ///< under mutex_
  std::thread syncer_;
};

}  // namespace flagsim
