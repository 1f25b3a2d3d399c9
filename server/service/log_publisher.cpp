#include "server/service/log_publisher.hpp"

#include <cmath>
#include <cstdio>
#include <lcm/lcm-cpp.hpp>
#include <stdexcept>

namespace flagsim {
namespace {

/// Bytes an event takes in the file: sync word, event number, timestamp, two lengths, then
/// the channel and the data.
constexpr uint64_t kEventHeaderBytes = 4 + 8 + 8 + 4 + 4;

}  // namespace

LogPublisher::LogPublisher(const std::string& path, int64_t start_utime)
    : path_(path), log_(std::make_unique<lcm::LogFile>(path, "w")), start_utime_(start_utime) {
  if (!log_->good()) throw std::runtime_error("cannot write the log file " + path);
}

LogPublisher::~LogPublisher() = default;

int64_t LogPublisher::UtimeAt(double time) const { return start_utime_ + std::llround(time * 1e6); }

void LogPublisher::AdvanceTo(double time) {
  if (time < time_) return;
  while (!paced_.empty() && paced_.front().departure <= time) {
    const Paced& message = paced_.front();
    Write(message.departure, message.channel, message.bytes.data(), message.bytes.size());
    paced_.pop_front();
  }
  time_ = time;
}

void LogPublisher::Publish(const std::string& channel, const uint8_t* data, size_t size) {
  Write(time_, channel, data, size);
}

void LogPublisher::Enqueue(const std::string& channel, std::vector<uint8_t> bytes) {
  const double departure = pacing_.Depart(time_, bytes.size());
  paced_.push_back(Paced{departure, channel, std::move(bytes)});
}

void LogPublisher::Close() {
  while (!paced_.empty()) AdvanceTo(paced_.front().departure);
  if (std::fflush(log_->getFilePtr()) != 0) {
    throw std::runtime_error("writing " + path_ + " failed after " + std::to_string(events_) + " events");
  }
}

void LogPublisher::Write(double time, const std::string& channel, const uint8_t* data, size_t size) {
  lcm::LogEvent event;
  event.timestamp = UtimeAt(time);
  event.channel = channel;
  event.datalen = static_cast<int32_t>(size);
  event.data = const_cast<uint8_t*>(data);  // LCM's writer takes it non-const; it only reads
  if (log_->writeEvent(&event) != 0) {
    throw std::runtime_error("writing " + path_ + " failed after " + std::to_string(events_) +
                             " events (is the disk full?)");
  }
  ++events_;
  bytes_ += kEventHeaderBytes + channel.size() + size;
}

}  // namespace flagsim
