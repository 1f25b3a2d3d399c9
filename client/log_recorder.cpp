#include "client/log_recorder.hpp"

#include "messages/utime.hpp"

namespace flagsim {

LogRecorder::LogRecorder(Bus& bus, const Channels& channels, const std::string& path)
    : bus_(bus), checkpoint_channel_(channels.checkpoint), log_(path) {
  // A deep queue: a recorder must not drop what arrives in bursts between two Handle() calls.
  subscription_ = bus.Subscribe(
      channels.AllChannels(),
      [this](const std::string& channel, const uint8_t* data, size_t size) { Write(channel, data, size); },
      10000);
}

LogRecorder::~LogRecorder() { bus_.Unsubscribe(subscription_); }

bool LogRecorder::KeyframeRequestDue(double now) {
  if (checkpoints_ > 0 || asks_ >= kAsks || (asks_ > 0 && now - asked_ < kAskInterval)) return false;
  ++asks_;
  asked_ = now;
  return true;
}

// Stamped with the receive time, as lcm-logger stamps events. A failed write ends the log and
// returns nothing to LCM's C dispatch.
void LogRecorder::Write(const std::string& channel, const uint8_t* data, size_t size) {
  if (log_.Write(UnixMicros(), channel, data, size) && channel == checkpoint_channel_) ++checkpoints_;
}

}  // namespace flagsim
