#include "client/gateway/channel_feed.hpp"

namespace flagsim::gateway {

void ChannelFeed::Publish(uint64_t timestamp_ns, std::string payload) {
  PublishLazily(timestamp_ns, nullptr);
  messages_.back().payload = std::make_shared<const std::string>(std::move(payload));
}

void ChannelFeed::PublishLazily(uint64_t timestamp_ns, std::function<std::string()> make) {
  FeedMessage message;
  message.number = ++count_;
  message.timestamp_ns = timestamp_ns;
  message.make = std::move(make);
  messages_.push_back(std::move(message));
  while (messages_.size() > capacity_) messages_.pop_front();
}

const FeedMessage* ChannelFeed::Next(uint64_t after) {
  for (FeedMessage& message : messages_) {
    if (message.number <= after) continue;
    if (!message.payload) {
      message.payload = std::make_shared<const std::string>(message.make());
      message.make = nullptr;
    }
    return &message;
  }
  return nullptr;
}

}  // namespace flagsim::gateway
