#include "client/log_recorder.hpp"

#include <lcm/lcm-cpp.hpp>
#include <stdexcept>

#include "messages/utime.hpp"

namespace flagsim {

LogRecorder::LogRecorder(Bus& bus, const std::string& channel_regex, const std::string& path)
    : bus_(bus), log_(std::make_unique<lcm::LogFile>(path, "w")) {
  if (!log_->good()) throw std::runtime_error("cannot write the log file " + path);
  // A deep queue: a recorder must not drop what arrives in bursts between two Handle() calls.
  subscription_ = bus.Subscribe(
      channel_regex,
      [this](const std::string& channel, const uint8_t* data, size_t size) { Write(channel, data, size); },
      10000);
}

LogRecorder::~LogRecorder() { bus_.Unsubscribe(subscription_); }

void LogRecorder::Write(const std::string& channel, const uint8_t* data, size_t size) {
  lcm::LogEvent event;
  event.eventnum = events_;
  event.timestamp = UnixMicros();  // receive time, as lcm-logger stamps events
  event.channel = channel;
  event.datalen = static_cast<int32_t>(size);
  event.data = const_cast<uint8_t*>(data);
  if (failed_ || log_->writeEvent(&event) != 0) {
    failed_ = true;  // no exceptions through LCM's C dispatch
    return;
  }
  ++events_;
  bytes_ += size;
}

}  // namespace flagsim
