// The newest messages of one gateway channel, numbered, for clients that each take them at
// their own pace. A client remembers the number it was last sent and asks for the next one
// it has not had: with capacity 1 that is always the newest (latest wins: a slow client skips,
// never queues); the ACK channel keeps more so that a client sees every answer unless it falls
// far behind. A payload may be given as a function that makes it, run once, by the first client
// that takes the message (a JPEG nobody takes is never encoded).
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <string>

namespace flagsim::gateway {

struct FeedMessage {
  uint64_t number = 0;                         ///< 1, 2, ... in publishing order
  uint64_t timestamp_ns = 0;                   ///< the message's own time, ns since the Unix epoch
  std::shared_ptr<const std::string> payload;  ///< null until made
  std::function<std::string()> make;           ///< makes the payload, when given lazily
};

class ChannelFeed {
 public:
  explicit ChannelFeed(size_t capacity = 1) : capacity_(capacity) {}

  void Publish(uint64_t timestamp_ns, std::string payload);
  void PublishLazily(uint64_t timestamp_ns, std::function<std::string()> make);

  /// The oldest kept message numbered above `after`, its payload made; null if none.
  const FeedMessage* Next(uint64_t after);
  /// The number of the newest message, 0 before the first.
  uint64_t newest() const { return messages_.empty() ? 0 : messages_.back().number; }

 private:
  size_t capacity_;
  uint64_t count_ = 0;
  std::deque<FeedMessage> messages_;
};

}  // namespace flagsim::gateway
