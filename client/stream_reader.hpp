// Waiting for messages of one type on one channel, decoded with every length checked.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <string>

#include "messages/bus.hpp"
#include "messages/checked_decode.hpp"
#include "messages/utime.hpp"

namespace flagsim {

/// Largest message a reader accepts: a STATE of a 512 x 512 flag is about 3 MB.
constexpr size_t kMaxStreamMessageBytes = 16 * 1024 * 1024;

/// A bus handler that calls `on_message` for each valid Message and counts the rest in `invalid`.
template <class Message>
Bus::Handler DecodingHandler(std::function<void(const Message&)> on_message, int64_t* invalid = nullptr) {
  return [on_message, invalid](const std::string&, const uint8_t* data, size_t size) {
    std::string error;
    const std::optional<Message> message =
        wire::CheckedDecode<Message>(data, size, kMaxStreamMessageBytes, &error);
    if (message) {
      on_message(*message);
    } else if (invalid != nullptr) {
      ++*invalid;
    }
  };
}

/// Calls `on_message` for each valid Message on `channel` while Handle() runs; counts the rest.
template <class Message>
size_t SubscribeDecoded(Bus& bus, const std::string& channel, std::function<void(const Message&)> on_message,
                        int64_t* invalid = nullptr, int queue_capacity = 30) {
  return bus.Subscribe(channel, DecodingHandler<Message>(std::move(on_message), invalid), queue_capacity);
}

/// Handles the bus until `done()` or `timeout` seconds pass; true if done.
inline bool HandleUntil(Bus& bus, double timeout, const std::function<bool()>& done) {
  const double end = MonotonicSeconds() + timeout;
  while (!done()) {
    const double left = end - MonotonicSeconds();
    if (left <= 0) return false;
    bus.Handle(static_cast<int>(std::ceil(1000 * std::min(left, 0.1))));
  }
  return true;
}

/// The next Message on `channel` within `timeout` seconds.
template <class Message>
std::optional<Message> AwaitMessage(Bus& bus, const std::string& channel, double timeout) {
  std::optional<Message> received;
  const size_t token =
      SubscribeDecoded<Message>(bus, channel, [&received](const Message& message) { received = message; });
  HandleUntil(bus, timeout, [&received] { return received.has_value(); });
  bus.Unsubscribe(token);
  return received;
}

}  // namespace flagsim
