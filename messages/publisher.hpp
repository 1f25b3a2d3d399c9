// Where outgoing messages go: the bus for a live server (bus.hpp), an event log for a render
// (server/service/log_publisher.hpp). Code that only publishes takes a Publisher, so it runs
// the same against either.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace flagsim {

class Publisher {
 public:
  virtual ~Publisher() = default;

  /// Sends one encoded message on `channel`.
  virtual void Publish(const std::string& channel, const uint8_t* data, size_t size) = 0;

  /// Encodes an lcm-gen message and sends it.
  template <class Message>
  void Publish(const std::string& channel, const Message& message) {
    const std::vector<uint8_t> bytes = Encode(message);
    Publish(channel, bytes.data(), bytes.size());
  }

  /// The message's bytes as they go on the wire.
  template <class Message>
  static std::vector<uint8_t> Encode(const Message& message) {
    std::vector<uint8_t> bytes(static_cast<size_t>(message.getEncodedSize()));
    message.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
    return bytes;
  }
};

}  // namespace flagsim
