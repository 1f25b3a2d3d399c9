#include "messages/event_log_reader.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace flagsim {
namespace {

uint64_t BigEndian(const uint8_t* bytes, int count) {
  uint64_t value = 0;
  for (int i = 0; i < count; ++i) value = (value << 8) | bytes[i];
  return value;
}

std::string Hex(uint32_t value) {
  char text[16];
  std::snprintf(text, sizeof(text), "0x%08X", value);
  return text;
}

}  // namespace

EventLogReader::EventLogReader(const std::string& path) : path_(path), file_(std::fopen(path.c_str(), "rb")) {
  struct stat status {};
  if (!file_ || fstat(fileno(file_.get()), &status) != 0) {
    throw std::runtime_error("cannot read " + path + ": " + std::strerror(errno));
  }
  if (S_ISDIR(status.st_mode)) throw std::runtime_error("cannot read " + path + ": it is a directory");
  size_ = static_cast<uint64_t>(status.st_size);
}

bool EventLogReader::Next(LogEvent* event, const ChannelFilter& wanted) {
  if (end_ != End::kNotYet) return false;
  Header header;
  if (!ReadHeader(&header) || !CheckHeader(header) || !ReadBody(header, event, wanted)) return false;
  event->number = header.number;
  event->timestamp = header.timestamp;
  event->offset = offset_;
  offset_ += kHeaderBytes + uint64_t(header.channel_bytes) + uint64_t(header.data_bytes);
  ++events_;
  return true;
}

// 28 bytes => sync word, event number, timestamp, channel and data lengths
bool EventLogReader::ReadHeader(Header* header) {
  uint8_t bytes[kHeaderBytes];
  const size_t got = std::fread(bytes, 1, kHeaderBytes, file_.get());
  if (got < kHeaderBytes) {
    if (std::ferror(file_.get()))
      return Stop(End::kReadError, std::string("read error: ") + std::strerror(errno));
    if (got == 0) return Stop(End::kClean, "");
    if (!StartsWithSync(bytes, got)) return StopAtBadSync(bytes, got);
    return Stop(End::kTruncated, "cut short inside its header (" + std::to_string(got) + " of " +
                                     std::to_string(kHeaderBytes) + " bytes are there)");
  }
  header->sync = static_cast<uint32_t>(BigEndian(bytes, 4));
  header->number = static_cast<int64_t>(BigEndian(bytes + 4, 8));
  header->timestamp = static_cast<int64_t>(BigEndian(bytes + 12, 8));
  header->channel_bytes = static_cast<int32_t>(BigEndian(bytes + 20, 4));
  header->data_bytes = static_cast<int32_t>(BigEndian(bytes + 24, 4));
  return true;
}

// Lengths are checked before anything is allocated or read: a header that lies stops here.
bool EventLogReader::CheckHeader(const Header& header) {
  if (header.sync != kSyncWord) {
    uint8_t bytes[4];
    for (int i = 0; i < 4; ++i) bytes[i] = uint8_t(header.sync >> (24 - 8 * i));
    return StopAtBadSync(bytes, 4);
  }
  if (header.channel_bytes < 1 || header.channel_bytes > kMaxChannelBytes) {
    return Stop(End::kCorrupt, "channel length " + std::to_string(header.channel_bytes) + "; allowed 1 .. " +
                                   std::to_string(kMaxChannelBytes));
  }
  if (header.data_bytes < 0 || header.data_bytes > kMaxDataBytes) {
    return Stop(End::kCorrupt, "data length " + std::to_string(header.data_bytes) + "; allowed 0 .. " +
                                   std::to_string(kMaxDataBytes));
  }
  const uint64_t body = uint64_t(header.channel_bytes) + uint64_t(header.data_bytes);
  const uint64_t left = size_ - std::min(size_, offset_ + kHeaderBytes);
  if (body > left) {
    return Stop(End::kTruncated, "cut short (" + std::to_string(kHeaderBytes + left) + " of its " +
                                     std::to_string(kHeaderBytes + body) + " bytes are there)");
  }
  return true;
}

// channel, then the data (read, or skipped if not wanted)
bool EventLogReader::ReadBody(const Header& header, LogEvent* event, const ChannelFilter& wanted) {
  event->channel.assign(size_t(header.channel_bytes), '\0');
  if (std::fread(event->channel.data(), 1, event->channel.size(), file_.get()) != event->channel.size()) {
    return ReadFailed();
  }
  event->data.clear();
  if (wanted && !wanted(event->channel)) {
    if (fseeko(file_.get(), header.data_bytes, SEEK_CUR) != 0) return ReadFailed();
    return true;
  }
  event->data.resize(size_t(header.data_bytes));
  if (std::fread(event->data.data(), 1, event->data.size(), file_.get()) != event->data.size()) {
    return ReadFailed();
  }
  return true;
}

// The first `count` bytes of the sync word (all of it, or what a cut file holds of it).
bool EventLogReader::StartsWithSync(const uint8_t* bytes, size_t count) {
  for (size_t i = 0; i < std::min<size_t>(count, 4); ++i) {
    if (bytes[i] != uint8_t(kSyncWord >> (24 - 8 * i))) return false;
  }
  return true;
}

bool EventLogReader::StopAtBadSync(const uint8_t* bytes, size_t count) {
  if (offset_ == 0)
    return Stop(End::kCorrupt, "not an LCM event log (it does not start with " + Hex(kSyncWord) + ")");
  const uint32_t found = static_cast<uint32_t>(BigEndian(bytes, int(std::min<size_t>(count, 4))));
  return Stop(End::kCorrupt, "no sync word (" + Hex(found) + " where " + Hex(kSyncWord) + " belongs)");
}

// A body that was there when the file was opened but cannot be read now: an error, or the
// file shrank under us.
bool EventLogReader::ReadFailed() {
  if (std::ferror(file_.get()))
    return Stop(End::kReadError, std::string("read error: ") + std::strerror(errno));
  return Stop(End::kTruncated, "cut short (the file shrank while it was read)");
}

bool EventLogReader::Stop(End end, const std::string& what) {
  end_ = end;
  if (end != End::kClean) {
    problem_ =
        path_ + ": at byte " + std::to_string(offset_) + ", event " + std::to_string(events_) + ": " + what;
  }
  return false;
}

}  // namespace flagsim
