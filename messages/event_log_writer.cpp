#include "messages/event_log_writer.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <limits>
#include <stdexcept>

#include "messages/event_log_reader.hpp"

namespace flagsim {
namespace {

void PutBigEndian(uint64_t value, int count, uint8_t* bytes) {
  for (int i = 0; i < count; ++i) bytes[i] = uint8_t(value >> (8 * (count - 1 - i)));
}

/// What a failed write's errno means for the person reading the message.
std::string Cause(int error) {
  const std::string text = std::strerror(error);
  if (error == ENOSPC || error == EDQUOT) return "the disk is full (" + text + ")";
  if (error == EFBIG) return "the file reached the largest size allowed (" + text + ")";
  return text;
}

}  // namespace

EventLogWriter::EventLogWriter(const std::string& path, double sync_interval)
    : path_(path), fd_(::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644)) {
  if (fd_ < 0) throw std::runtime_error("cannot write the log file " + path + ": " + std::strerror(errno));
  syncer_ = std::thread([this, sync_interval] { SyncEvery(sync_interval); });
}

EventLogWriter::~EventLogWriter() { Close(); }

// header (sync word, event number, timestamp, channel and data lengths) | channel | data, in one
// writev: the kernel has the whole event, or the log ends here.
bool EventLogWriter::Write(int64_t timestamp, const std::string& channel, const uint8_t* data, size_t size) {
  if (failed_ || fd_ < 0) return false;
  if (const int error = sync_errno_.load(); error != 0) return Fail("syncing it failed: " + Cause(error));
  if (channel.empty() || channel.size() > size_t(EventLogReader::kMaxChannelBytes) ||
      size > size_t(std::numeric_limits<int32_t>::max())) {
    return Fail("an event on '" + channel + "' of " + std::to_string(size) +
                " bytes does not fit an LCM log (channel 1 .. 999 bytes, data under 2 GiB)");
  }
  uint8_t header[EventLogReader::kHeaderBytes];
  PutBigEndian(EventLogReader::kSyncWord, 4, header);
  PutBigEndian(uint64_t(events_), 8, header + 4);
  PutBigEndian(uint64_t(timestamp), 8, header + 12);
  PutBigEndian(channel.size(), 4, header + 20);
  PutBigEndian(size, 4, header + 24);
  const iovec parts[3] = {{header, sizeof(header)},
                          {const_cast<char*>(channel.data()), channel.size()},
                          {const_cast<uint8_t*>(data), size}};
  const size_t total = sizeof(header) + channel.size() + size;
  if (!WriteAll(parts, 3, total)) return false;
  ++events_;
  bytes_ += total;
  written_.store(bytes_);
  return true;
}

// A short write (a file that reached a limit, a signal) goes on from where it stopped; an error
// ends the log.
bool EventLogWriter::WriteAll(const iovec* parts, int count, size_t total) {
  iovec rest[3];
  std::copy(parts, parts + count, rest);
  iovec* next = rest;
  for (size_t done = 0; done < total;) {
    const ssize_t wrote = ::writev(fd_, next, count - int(next - rest));
    if (wrote < 0 && errno == EINTR) continue;
    if (wrote <= 0) return Fail(Cause(wrote < 0 ? errno : ENOSPC));
    done += size_t(wrote);
    for (size_t skip = size_t(wrote); skip > 0;) {  // past what went out
      const size_t taken = std::min(skip, next->iov_len);
      next->iov_base = static_cast<uint8_t*>(next->iov_base) + taken;
      next->iov_len -= taken;
      skip -= taken;
      if (next->iov_len == 0) ++next;
    }
  }
  return true;
}

// The file back to its whole events, so that it reads to its end; and the message.
bool EventLogWriter::Fail(const std::string& what) {
  failed_ = true;
  const bool whole = ::ftruncate(fd_, off_t(bytes_)) == 0 || ::lseek(fd_, 0, SEEK_END) == off_t(bytes_);
  error_ = "writing " + path_ + " stopped: " + what + "; the log holds its first " + std::to_string(events_) +
           " events, " + std::to_string(bytes_) + " bytes, " +
           (whole ? "every one whole" : "and perhaps part of one more, which readers stop before");
  return false;
}

bool EventLogWriter::Close() {
  if (fd_ < 0) return !failed_;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  syncer_.join();
  if (!failed_ && sync_errno_.load() != 0) Fail("syncing it failed: " + Cause(sync_errno_.load()));
  if (!failed_ && ::fdatasync(fd_) != 0 && errno != EINVAL) Fail("syncing it failed: " + Cause(errno));
  ::close(fd_);
  fd_ = -1;
  return !failed_;
}

// The syncing thread: every `interval` s, fdatasync if whole events were written since the last.
// EINVAL: a file that cannot be synced (a device, a pipe), which is no failure.
void EventLogWriter::SyncEvery(double interval) {
  uint64_t synced = 0;
  std::unique_lock<std::mutex> lock(mutex_);
  while (!wake_.wait_for(lock, std::chrono::duration<double>(interval), [this] { return stopping_; })) {
    const uint64_t written = written_.load();
    if (written == synced) continue;
    lock.unlock();
    if (synced == 0) SyncDirectoryOnce();
    const auto start = std::chrono::steady_clock::now();
    if (::fdatasync(fd_) == 0) {
      synced = written;
      ++syncs_;
      sync_nanoseconds_ += std::chrono::nanoseconds(std::chrono::steady_clock::now() - start).count();
    } else if (errno != EINVAL) {
      sync_errno_.store(errno);
    }
    lock.lock();
  }
}

// A new file's name is in its directory, which needs a sync of its own to survive a power loss.
void EventLogWriter::SyncDirectoryOnce() {
  std::filesystem::path directory = std::filesystem::path(path_).parent_path();
  if (directory.empty()) directory = ".";
  const int fd = ::open(directory.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

}  // namespace flagsim
