#include "server/service/paced_publisher.hpp"

#include <algorithm>
#include <chrono>

#include "messages/utime.hpp"

namespace flagsim {

PacedPublisher::PacedPublisher(Publisher& publisher) : publisher_(publisher), thread_([this] { Run(); }) {}

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
  return queue_.size() + (publishing_ ? 1 : 0);
}

void PacedPublisher::WaitUntilSent() {
  std::unique_lock<std::mutex> lock(mutex_);
  sent_.wait(lock, [this] { return queue_.empty() && !publishing_; });
}

// queue => departure time from the pacing => sleep until then => publish
void PacedPublisher::Run() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (true) {
    wake_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
    if (queue_.empty()) return;  // stopping, and all sent
    Item item = std::move(queue_.front());
    queue_.pop_front();
    publishing_ = true;
    lock.unlock();
    const double departure = pacing_.Depart(MonotonicSeconds(), item.bytes.size());
    const double wait = departure - MonotonicSeconds();
    if (wait > 0) std::this_thread::sleep_for(std::chrono::duration<double>(wait));
    publisher_.Publish(item.channel, item.bytes.data(), item.bytes.size());
    lock.lock();
    publishing_ = false;
    if (queue_.empty()) sent_.notify_all();
  }
}

}  // namespace flagsim
