// Commands sent on the bus without blocking, for a gateway that serves many clients from one
// event loop. Each command is resent with the same sequence number every kRetryInterval until
// its ACK comes (the server applies a retry once) or `timeout` passes; then its callback runs
// once with the outcome. The caller feeds ACKs in (OnAck) and calls Tick when NextDue says.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <string>

#include "client/command_client.hpp"
#include "flagsim/ack_t.hpp"
#include "messages/bus.hpp"
#include "messages/command_mac.hpp"

namespace flagsim::gateway {

class CommandRelay {
 public:
  static constexpr double kRetryInterval = CommandClient::kRetryInterval;  ///< s
  using Done = std::function<void(const CommandOutcome& outcome, int64_t sequence)>;

  /// `client_id` goes into every command; ACKs for other ids are not ours. `signer` stamps each
  /// send (command_mac.hpp): unsigned by default.
  CommandRelay(Bus& bus, std::string client_id, double timeout, CommandSigner signer = {});

  /// Stamps `command` (client id, sequence, time), publishes it on `channel`, and calls `done`
  /// on its ACK or at the timeout. Returns the sequence number.
  template <class Command>
  int64_t Send(const std::string& channel, Command command, double now, Done done) {
    command.client_id = client_id_;
    command.sequence = ++sequence_;
    Pending pending;
    pending.publish = [this, channel, command]() mutable {
      signer_.Stamp(channel, command);
      bus_.Publish(channel, command);
    };
    pending.done = std::move(done);
    pending.deadline = now + timeout_;
    pending.next_send = now + kRetryInterval;
    pending.publish();
    pending_.emplace(command.sequence, std::move(pending));
    return command.sequence;
  }

  /// An ACK from the bus: completes the command it answers, if it is ours.
  void OnAck(const ack_t& ack);
  /// Resends what is due and times out what has waited `timeout` (their callbacks run last, so
  /// they may send again).
  void Tick(double now);
  /// When Tick is next needed (s, the clock `now` is on); +infinity with nothing pending.
  double NextDue() const;

  const std::string& client_id() const { return client_id_; }
  size_t pending() const { return pending_.size(); }

 private:
  struct Pending {
    std::function<void()> publish;
    Done done;
    double deadline = 0;
    double next_send = 0;
  };

  Bus& bus_;
  std::string client_id_;
  double timeout_;
  CommandSigner signer_;
  int64_t sequence_ = 0;
  std::map<int64_t, Pending> pending_;  ///< by sequence
};

/// "flagctl-serve-<pid>-<8 hex digits>".
std::string NewGatewayClientId();

}  // namespace flagsim::gateway
