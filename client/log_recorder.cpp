#include "client/log_recorder.hpp"

#include "messages/utime.hpp"

namespace flagsim {

LogRecorder::LogRecorder(Bus& bus, const std::string& channel_regex, const std::string& path)
    : bus_(bus), log_(path) {
  // A deep queue: a recorder must not drop what arrives in bursts between two Handle() calls.
  subscription_ = bus.Subscribe(
      channel_regex,
      [this](const std::string& channel, const uint8_t* data, size_t size) { Write(channel, data, size); },
      10000);
}

LogRecorder::~LogRecorder() { bus_.Unsubscribe(subscription_); }

// Stamped with the receive time, as lcm-logger stamps events. A failed write ends the log and
// returns nothing to LCM's C dispatch.
void LogRecorder::Write(const std::string& channel, const uint8_t* data, size_t size) {
  log_.Write(UnixMicros(), channel, data, size);
}

}  // namespace flagsim
