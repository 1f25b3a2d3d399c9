// Publishing at a bounded rate from a thread of its own. LCM 1.3.1 over UDP loses bursts (a
// receiver's socket buffer overflows), so tiles leave no faster than PublishPacing allows
// (token buckets on messages and bytes), in the order they were queued, while the server's
// loop goes on stepping.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "messages/publisher.hpp"
#include "server/service/publish_pacing.hpp"

namespace flagsim {

class PacedPublisher {
 public:
  explicit PacedPublisher(Publisher& publisher);
  ~PacedPublisher();  ///< publishes what is queued, then stops
  PacedPublisher(const PacedPublisher&) = delete;
  PacedPublisher& operator=(const PacedPublisher&) = delete;

  /// Queues an encoded message.
  void Enqueue(const std::string& channel, std::vector<uint8_t> bytes);

  template <class Message>
  void Enqueue(const std::string& channel, const Message& message) {
    Enqueue(channel, Publisher::Encode(message));
  }

  /// Messages not yet published: those queued and the one on its way out.
  size_t queued() const;

  /// Waits until every message queued so far has been published.
  void WaitUntilSent();

 private:
  struct Item {
    std::string channel;
    std::vector<uint8_t> bytes;
  };
  void Run();

  Publisher& publisher_;
  PublishPacing pacing_;  ///< on wall time, s
  mutable std::mutex mutex_;
  std::condition_variable wake_;  ///< a message queued, or stopping
  std::condition_variable sent_;  ///< the last message queued published
  std::deque<Item> queue_;
  bool publishing_ = false;  ///< an item is out of queue_ but not yet published
  bool stopping_ = false;
  std::thread thread_;
};

}  // namespace flagsim
