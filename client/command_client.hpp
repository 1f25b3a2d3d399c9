// Sending one command and waiting for its ACK. The command is resent with the same sequence
// number until an answer comes or the timeout passes (LCM over UDP can lose either way); the
// server applies a retried command once. Each send is dated anew and, with a key, signed anew
// (command_mac.hpp), so that a server with keys tells a retry from a replay.
#pragma once

#include <algorithm>
#include <cstdint>
#include <functional>
#include <random>
#include <string>

#include "flagsim/ack_t.hpp"
#include "messages/bus.hpp"
#include "messages/channels.hpp"
#include "messages/checked_decode.hpp"
#include "messages/command_mac.hpp"
#include "messages/utime.hpp"

namespace flagsim {

struct CommandOutcome {
  enum Result { kAccepted, kRejected, kNoAnswer };
  Result result = kNoAnswer;
  std::string reason;     ///< the server's, when rejected
  int64_t step = -1;      ///< when accepted: the step at whose start it took effect
  int64_t server_id = 0;  ///< the answering server's
  int other_servers = 0;  ///< other servers it hears on the prefix: they took the command too
};

/// What an ACK says about its command.
CommandOutcome OutcomeOf(const ack_t& ack);

class CommandClient {
 public:
  static constexpr double kRetryInterval = 0.5;  ///< s between resends

  /// `signer` stamps every command sent: unsigned by default. The timeout and the resends run on
  /// `clock` (s, monotonic); a test that drives an in-process server on a clock of its own gives
  /// the client the same one.
  CommandClient(Bus& bus, const Channels& channels, double timeout_seconds, CommandSigner signer = {},
                std::function<double()> clock = MonotonicSeconds);
  ~CommandClient();  ///< stops listening for ACKs: a client may go before its bus
  CommandClient(const CommandClient&) = delete;
  CommandClient& operator=(const CommandClient&) = delete;

  /// Fills in client_id and sequence, then on each send utime (and key_id and mac with a key),
  /// publishes on `channel`, and waits for the ACK.
  template <class Command>
  CommandOutcome Send(const std::string& channel, Command command) {
    command.client_id = client_id_;
    command.sequence = ++sequence_;
    return SendRepeatedly(command.sequence, [&] {
      signer_.Stamp(channel, command);
      bus_.Publish(channel, command);
    });
  }

  const std::string& client_id() const { return client_id_; }
  /// The sequence number of the last command sent (0 before any).
  int64_t last_sequence() const { return sequence_; }

  /// Work to do between looks at the bus while an answer is awaited (an in-process server's
  /// loop, say); by default the client only waits on the bus.
  void WhileWaiting(std::function<void()> work) { while_waiting_ = std::move(work); }

 private:
  template <class Publish>
  CommandOutcome SendRepeatedly(int64_t sequence, Publish publish) {
    awaited_ = sequence;
    outcome_ = CommandOutcome{};
    const double start = clock_();
    double next_send = start;
    while (outcome_.result == CommandOutcome::kNoAnswer) {
      const double now = clock_();
      if (now - start >= timeout_) break;
      if (now >= next_send) {
        publish();
        next_send = now + kRetryInterval;
      }
      if (while_waiting_) {
        while_waiting_();
        bus_.HandleAll();
      } else {
        bus_.Handle(static_cast<int>(1000 * std::max(0.001, std::min(next_send, start + timeout_) - now)));
      }
    }
    return outcome_;
  }

  void OnAck(const uint8_t* data, size_t size);

  Bus& bus_;
  double timeout_;
  CommandSigner signer_;
  std::function<double()> clock_;
  std::string client_id_;
  int64_t sequence_ = 0;
  int64_t awaited_ = -1;
  std::function<void()> while_waiting_;
  CommandOutcome outcome_;
  size_t ack_subscription_ = 0;
};

}  // namespace flagsim
