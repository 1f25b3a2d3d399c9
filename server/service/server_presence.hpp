// Other servers on the same channel prefix. Each flagd draws a random id at its start and
// carries it in STATUS, STATE and ACK. A STATUS with another id means a second server: it takes
// every command too (flagctl would see one ACK and think it steered the only flag), and the two
// STATE and frame streams interleave. The first STATUS of each other id is logged as an error;
// how many others were heard within kForgetAfter goes into STATUS and every ACK, so clients
// can say so.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <string>

#include "messages/bus.hpp"
#include "messages/channels.hpp"
#include "messages/utime.hpp"

namespace flagsim {

class ServerPresence {
 public:
  static constexpr double kForgetAfter = 3.0;   ///< s without a server's STATUS: it has gone
  static constexpr size_t kMaxRemembered = 64;  ///< ids kept, so a flood of forged ones is bounded

  /// What becomes of a STATUS that does not decode: (channel, why) to be counted and logged.
  using DropSink = std::function<void(const std::string& channel, const std::string& reason)>;

  /// Draws this server's id and listens on `channels.status`. `clock` gives monotonic seconds;
  /// undecodable STATUS messages go to `dropped` (none: ignored).
  ServerPresence(Bus& bus, const Channels& channels, std::function<double()> clock = MonotonicSeconds,
                 DropSink dropped = nullptr);

  /// Random, positive, never 0 (0 marks a message no live server published: a render).
  int64_t id() const { return id_; }
  /// Other servers whose STATUS came within the last kForgetAfter seconds.
  int others() const;

 private:
  void OnStatus(const uint8_t* data, size_t size);

  std::function<double()> clock_;
  DropSink dropped_;
  std::string channel_;  ///< STATUS, with the prefix
  std::string prefix_;
  int64_t id_;
  std::map<int64_t, double> heard_;  ///< another server's id => when its STATUS last came
  BusSubscriptions subscriptions_;  ///< last: dropped first, before what the handler uses
};

}  // namespace flagsim
