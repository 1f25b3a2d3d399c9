#include "server/service/log_publisher.hpp"

#include <cmath>
#include <stdexcept>

namespace flagsim {

LogPublisher::LogPublisher(const std::string& path, int64_t start_utime)
    : path_(path), log_(path), start_utime_(start_utime) {}

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
  if (!log_.Close()) throw std::runtime_error(log_.error());
}

void LogPublisher::Write(double time, const std::string& channel, const uint8_t* data, size_t size) {
  if (!log_.Write(UtimeAt(time), channel, data, size)) throw std::runtime_error(log_.error());
}

}  // namespace flagsim
