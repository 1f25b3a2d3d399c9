// The transport seam: an LCM instance built from a URL, publishing encoded messages and
// delivering raw bytes (decode them with CheckedDecode). Unit tests build it on memq://.
// One thread subscribes, calls Handle() and uses the typed Publish; Publish of raw bytes may
// also be called from other threads (LCM serialises its sends). A Bus is a Publisher (the
// other is an event log), so the paced publisher can feed either.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "messages/publisher.hpp"

namespace lcm {
class LCM;
class ReceiveBuffer;
}  // namespace lcm

namespace flagsim {

class Bus : public Publisher {
 public:
  /// Raw bytes of one message on `channel`, exactly as received.
  using Handler = std::function<void(const std::string& channel, const uint8_t* data, size_t size)>;

  /// `url` "" means LCM_DEFAULT_URL, else LCM's default (udpm://239.255.76.67:7667?ttl=0).
  /// Throws std::runtime_error naming the URL when LCM cannot start on it.
  explicit Bus(const std::string& url);
  ~Bus() override;
  Bus(const Bus&) = delete;
  Bus& operator=(const Bus&) = delete;

  /// The URL after defaults: what `url` "" resolves to.
  static std::string ResolveUrl(const std::string& url);
  /// For a udpm:// URL without one, asks for a socket receive buffer of `bytes` (LCM drops
  /// bursts with its default one); other URLs come back unchanged.
  static std::string WithReceiveBuffer(const std::string& url, int64_t bytes);

  void Publish(const std::string& channel, const uint8_t* data, size_t size) override;

  /// Safe from any thread: publishing is serialised (LCM's tcpq:// provider writes one stream,
  /// which two threads publishing at once would interleave; udpm:// does not need it).
  template <class Message>
  void Publish(const std::string& channel, const Message& message) {
    std::vector<uint8_t> bytes(static_cast<size_t>(message.getEncodedSize()));
    message.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
    Publish(channel, bytes.data(), bytes.size());
  }

  /// `channel` may be a regular expression. `queue_capacity`: messages LCM holds for this
  /// subscription between Handle() calls before it drops new ones. Returns a token for
  /// Unsubscribe; handlers live until then or until the bus goes.
  size_t Subscribe(const std::string& channel, Handler handler, int queue_capacity = 30);
  void Unsubscribe(size_t token);

  /// Waits up to `timeout_ms` for one message and dispatches it. Returns true if one was handled.
  bool Handle(int timeout_ms);
  /// Dispatches every message already waiting, without blocking.
  void HandleAll();
  /// A file descriptor that becomes readable when a message waits: for an event loop that
  /// watches it and calls HandleAll() (the gateway's).
  int fileno() const;

  uint64_t bytes_published() const { return bytes_published_.load(); }
  const std::string& url() const { return url_; }

 private:
  struct Subscriber;
  std::string url_;
  std::unique_ptr<lcm::LCM> lcm_;
  std::vector<std::unique_ptr<Subscriber>> subscribers_;
  std::mutex publishing_;  ///< one publish at a time
  std::atomic<uint64_t> bytes_published_{0};
};

/// The subscriptions an object makes on a bus, dropped when it goes: its handlers capture it, so
/// a bus that outlives it (a server restarted on the same bus in one process) must not call them.
class BusSubscriptions {
 public:
  explicit BusSubscriptions(Bus& bus) : bus_(bus) {}
  ~BusSubscriptions() {
    for (const size_t token : tokens_) bus_.Unsubscribe(token);
  }
  BusSubscriptions(const BusSubscriptions&) = delete;
  BusSubscriptions& operator=(const BusSubscriptions&) = delete;

  /// Bus::Subscribe, kept until this goes.
  void Subscribe(const std::string& channel, Bus::Handler handler, int queue_capacity = 30) {
    tokens_.push_back(bus_.Subscribe(channel, std::move(handler), queue_capacity));
  }

 private:
  Bus& bus_;
  std::vector<size_t> tokens_;
};

}  // namespace flagsim
