#include "server/service/publish_pacing.hpp"

#include <algorithm>

namespace flagsim {

void PublishPacing::Refill(double time) {
  if (time <= last_) return;
  const double elapsed = time - last_;  // infinite before the first message: full buckets
  message_tokens_ =
      std::min(message_tokens_ + elapsed * kMessagesPerSecond, kMessagesPerSecond * kBurstSeconds);
  byte_tokens_ = std::min(byte_tokens_ + elapsed * kBytesPerSecond, kBytesPerSecond * kBurstSeconds);
  last_ = time;
}

// (ready, bytes, buckets) => departure: the later of `ready` and the moment both buckets hold
// enough (or are full), then the tokens are spent.
double PublishPacing::Depart(double ready, size_t bytes) {
  double time = std::max(ready, last_);
  Refill(time);
  const double byte_need = std::min(double(bytes), kBytesPerSecond * kBurstSeconds);
  const double wait = std::max(
      {0.0, (1 - message_tokens_) / kMessagesPerSecond, (byte_need - byte_tokens_) / kBytesPerSecond});
  if (wait > 0) {
    time += wait;
    Refill(time);
  }
  message_tokens_ -= 1;
  byte_tokens_ -= double(bytes);
  return time;
}

}  // namespace flagsim
