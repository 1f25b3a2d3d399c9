#include "paced_publisher.hpp"

#include <algorithm>
#include <chrono>

#include "utime.hpp"

namespace flagsim {

PacedPublisher::PacedPublisher(Bus& bus) : bus_(bus), thread_([this] { Run(); }) {}

PacedPublisher::~PacedPublisher() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_one();
  thread_.join();
}

void PacedPublisher::Enqueue(const std::string& channel, std::vector<uint8_t> bytes) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    queue_.push_back(Item{channel, std::move(bytes)});
  }
  wake_.notify_one();
}

size_t PacedPublisher::queued() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return queue_.size();
}

// Two token buckets, refilled continuously: a message leaves when both hold enough.
void PacedPublisher::Run() {
  double message_tokens = kMessagesPerSecond * kBurstSeconds, byte_tokens = kBytesPerSecond * kBurstSeconds;
  double last = MonotonicSeconds();
  std::unique_lock<std::mutex> lock(mutex_);
  while (true) {
    wake_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
    if (queue_.empty()) return;  // stopping, and all sent
    Item item = std::move(queue_.front());
    queue_.pop_front();
    lock.unlock();
    while (true) {
      const double now = MonotonicSeconds();
      message_tokens =
          std::min(message_tokens + (now - last) * kMessagesPerSecond, kMessagesPerSecond * kBurstSeconds);
      byte_tokens = std::min(byte_tokens + (now - last) * kBytesPerSecond, kBytesPerSecond * kBurstSeconds);
      last = now;
      if (message_tokens >= 1 && byte_tokens >= double(item.bytes.size())) break;
      const double wait = std::max((1 - message_tokens) / kMessagesPerSecond,
                                   (double(item.bytes.size()) - byte_tokens) / kBytesPerSecond);
      std::this_thread::sleep_for(std::chrono::duration<double>(std::max(wait, 50e-6)));
    }
    message_tokens -= 1;
    byte_tokens -= double(item.bytes.size());
    bus_.Publish(item.channel, item.bytes.data(), item.bytes.size());
    lock.lock();
  }
}

}  // namespace flagsim
