// Reading an LCM event log (the format lcm-logger writes) without trusting it. The file is
// events back to back, nothing before the first; each is, big-endian and unpadded:
//
//   sync word 0xEDA1DA01 (4) | event number (8) | timestamp, us (8) | channel length (4) |
//   data length (4) | channel | data
//
// LCM 1.3.1's own reader (lcm::LogFile) ends a log cut short (a recorder killed mid-write)
// just as it ends a whole one, searches on past a damaged sync word for the next one (and
// drops the sound event before it), and crashes on an event claiming 2^31 - 1 data bytes.
// This reader checks each event's lengths against the bytes the file holds before reading,
// stops at the first event that is not whole or not sound, and says which and where.
#pragma once

#include <cstdint>
#include <cstdio>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace flagsim {

struct LogEvent {
  int64_t number = 0;     ///< the event number the writer gave it
  int64_t timestamp = 0;  ///< us since the Unix epoch: receive time, or simulated time in a render
  std::string channel;
  std::vector<uint8_t> data;  ///< the message; left empty when the caller did not want it
  uint64_t offset = 0;        ///< bytes from the file's start to the event's sync word
};

class EventLogReader {
 public:
  static constexpr uint32_t kSyncWord = 0xEDA1DA01;
  static constexpr uint64_t kHeaderBytes = 28;
  static constexpr int32_t kMaxChannelBytes = 999;     ///< LCM's own readers refuse longer ones
  static constexpr int32_t kMaxDataBytes = 256 << 20;  ///< no message of ours comes near

  enum class End {
    kNotYet,     ///< events may follow
    kClean,      ///< the file ended between two events
    kTruncated,  ///< the file ended inside an event: everything before it was read
    kCorrupt,    ///< an event's header makes no sense (no sync word, lengths out of range)
    kReadError,  ///< the system could not read the file
  };

  /// Opens `path`; throws std::runtime_error naming it and why if it cannot.
  explicit EventLogReader(const std::string& path);

  /// Channels whose data the caller wants; the others' data is skipped, not read.
  using ChannelFilter = std::function<bool(const std::string& channel)>;

  /// Reads the next whole, sound event into `event` (its data only if `wanted` is empty or
  /// says so). Returns false at the end of the log: then end() and problem() say how it ended.
  bool Next(LogEvent* event, const ChannelFilter& wanted = nullptr);

  End end() const { return end_; }
  /// How the log ended, naming the file, the byte and the event (counted from 0) where it
  /// stopped, e.g. "run.lcmlog: at byte 81920, event 57: cut short (3000 of its 9028 bytes
  /// are there)"; "" after a clean end.
  const std::string& problem() const { return problem_; }
  uint64_t offset() const { return offset_; }  ///< bytes read: the end of the last whole event
  uint64_t size() const { return size_; }      ///< of the file when it was opened
  int64_t events() const { return events_; }   ///< whole events read so far

 private:
  struct Header {
    uint32_t sync = 0;
    int64_t number = 0, timestamp = 0;
    int32_t channel_bytes = 0, data_bytes = 0;
  };
  bool ReadHeader(Header* header);
  bool CheckHeader(const Header& header);
  bool ReadBody(const Header& header, LogEvent* event, const ChannelFilter& wanted);
  static bool StartsWithSync(const uint8_t* bytes, size_t count);
  bool StopAtBadSync(const uint8_t* bytes, size_t count);
  bool ReadFailed();
  bool Stop(End end, const std::string& what);

  struct FileCloser {
    void operator()(std::FILE* file) const { std::fclose(file); }
  };
  std::string path_;
  std::unique_ptr<std::FILE, FileCloser> file_;
  uint64_t size_ = 0;
  uint64_t offset_ = 0;
  int64_t events_ = 0;
  End end_ = End::kNotYet;
  std::string problem_;
};

}  // namespace flagsim
