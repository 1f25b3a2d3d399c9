// The rate limit on tiles: two token buckets, one counting messages and one counting bytes,
// refilled continuously. LCM 1.3.1 over UDP loses bursts, so a live server sends its tiles no
// faster than this (paced_publisher.hpp, on wall time); a render stamps its logged tiles the
// same way on simulated time (log_publisher.hpp), so that a log plays back as the server sent.
#pragma once

#include <cstddef>
#include <limits>

namespace flagsim {

class PublishPacing {
 public:
  static constexpr double kMessagesPerSecond = 4000;
  static constexpr double kBytesPerSecond = 48e6;
  static constexpr double kBurstSeconds = 0.004;  ///< how much may leave at once

  /// When a message of `bytes` that is ready at `ready` (s, on any one clock) may leave, no
  /// earlier than the message before it; takes its tokens. A message larger than the byte
  /// bucket leaves once the bucket is full.
  double Depart(double ready, size_t bytes);

 private:
  /// Tokens earned from last_ to `time`, up to the buckets' sizes.
  void Refill(double time);

  double message_tokens_ = kMessagesPerSecond * kBurstSeconds;
  double byte_tokens_ = kBytesPerSecond * kBurstSeconds;
  double last_ = -std::numeric_limits<double>::infinity();  ///< s, the last departure
};

}  // namespace flagsim
