// Publishing at a bounded rate from a thread of its own. LCM 1.3.1 over UDP loses bursts (a
// receiver's socket buffer overflows), so tiles leave at most kMessagesPerSecond and
// kBytesPerSecond (token buckets), in the order they were queued, while the server's loop goes
// on stepping.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "bus.hpp"

namespace flagsim {

class PacedPublisher {
 public:
  static constexpr double kMessagesPerSecond = 4000;
  static constexpr double kBytesPerSecond = 48e6;
  static constexpr double kBurstSeconds = 0.004;  ///< how much may leave at once

  explicit PacedPublisher(Bus& bus);
  ~PacedPublisher();  ///< publishes what is queued, then stops
  PacedPublisher(const PacedPublisher&) = delete;
  PacedPublisher& operator=(const PacedPublisher&) = delete;

  /// Queues an encoded message.
  void Enqueue(const std::string& channel, std::vector<uint8_t> bytes);

  template <class Message>
  void Enqueue(const std::string& channel, const Message& message) {
    std::vector<uint8_t> bytes(static_cast<size_t>(message.getEncodedSize()));
    message.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
    Enqueue(channel, std::move(bytes));
  }

  /// Messages not yet published.
  size_t queued() const;

 private:
  struct Item {
    std::string channel;
    std::vector<uint8_t> bytes;
  };
  void Run();

  Bus& bus_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<Item> queue_;
  bool stopping_ = false;
  std::thread thread_;
};

}  // namespace flagsim
