#include "messages/bus.hpp"

#include <cstdlib>
#include <lcm/lcm-cpp.hpp>
#include <stdexcept>

namespace flagsim {

struct Bus::Subscriber {
  Handler handler;
  lcm::Subscription* subscription = nullptr;
  void OnMessage(const lcm::ReceiveBuffer* buffer, const std::string& channel) {
    handler(channel, static_cast<const uint8_t*>(buffer->data), buffer->data_size);
  }
};

std::string Bus::ResolveUrl(const std::string& url) {
  if (!url.empty()) return url;
  const char* from_environment = std::getenv("LCM_DEFAULT_URL");
  if (from_environment != nullptr && *from_environment != '\0') return from_environment;
  return "udpm://239.255.76.67:7667?ttl=0";
}

std::string Bus::WithReceiveBuffer(const std::string& url, int64_t bytes) {
  const std::string resolved = ResolveUrl(url);
  if (resolved.rfind("udpm://", 0) != 0 || resolved.find("recv_buf_size=") != std::string::npos) {
    return resolved;
  }
  const char separator = resolved.find('?') == std::string::npos ? '?' : '&';
  return resolved + separator + "recv_buf_size=" + std::to_string(bytes);
}

Bus::Bus(const std::string& url) : url_(ResolveUrl(url)), lcm_(std::make_unique<lcm::LCM>(url_)) {
  if (!lcm_->good()) throw std::runtime_error("cannot start LCM on " + url_);
}

Bus::~Bus() = default;

void Bus::Publish(const std::string& channel, const uint8_t* data, size_t size) {
  const std::lock_guard<std::mutex> lock(publishing_);
  lcm_->publish(channel, data, static_cast<unsigned int>(size));
  bytes_published_ += size;
}

size_t Bus::Subscribe(const std::string& channel, Handler handler, int queue_capacity) {
  auto subscriber = std::make_unique<Subscriber>();
  subscriber->handler = std::move(handler);
  subscriber->subscription = lcm_->subscribe(channel, &Subscriber::OnMessage, subscriber.get());
  subscriber->subscription->setQueueCapacity(queue_capacity);
  subscribers_.push_back(std::move(subscriber));
  return subscribers_.size() - 1;
}

void Bus::Unsubscribe(size_t token) {
  if (token >= subscribers_.size() || !subscribers_[token]) return;
  lcm_->unsubscribe(subscribers_[token]->subscription);
  subscribers_[token].reset();
}

bool Bus::Handle(int timeout_ms) { return lcm_->handleTimeout(timeout_ms) > 0; }

int Bus::fileno() const { return lcm_->getFileno(); }

void Bus::HandleAll() {
  while (Handle(0)) {
  }
}

}  // namespace flagsim
