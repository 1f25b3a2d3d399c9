// What flagctl's subcommands share to talk to a server: the bus and channels of one subcommand
// (Link), a command's round trip (SendCommand: command => ACK => the outcome printed, an exit
// code) and a table's latest message asked for and printed (AwaitAndPrint).
#pragma once

#include <algorithm>
#include <optional>
#include <ostream>
#include <string>

#include "client/command_client.hpp"
#include "client/flagctl_commands.hpp"
#include "client/stream_reader.hpp"
#include "flagsim/refresh_request_t.hpp"
#include "messages/bus.hpp"
#include "messages/channels.hpp"

namespace flagsim {

/// The bus and channels one subcommand talks on, and how it signs its commands.
struct Link {
  /// Throws std::runtime_error naming the key file when --key-file cannot be read.
  explicit Link(const Globals& globals);

  /// Says that no `what` came within the timeout; returns kNoAnswer.
  int NoAnswer(const std::string& what) const;

  Bus bus;
  Channels channels;
  const Globals& globals;
  CommandSigner signer;  ///< the first key of --key-file, or unsigned
};

/// The outcome printed (accepted at a step, or the server's reason); returns the exit code.
int Report(const Link& link, const CommandOutcome& outcome);

/// One command on `channel` of Channels, its ACK awaited and reported: its exit code.
template <class Command>
int SendCommand(const Globals& globals, std::string Channels::*channel, const Command& command) {
  Link link(globals);
  CommandClient client(link.bus, link.channels, globals.timeout, link.signer);
  return Report(link, client.Send(link.channels.*channel, command));
}

/// s to wait for the ACK of a REFRESH before taking a stream as it comes: nobody answers one
/// when lcm-logplayer plays a log, say.
constexpr double kRefreshAnswerWait = 1.0;

/// A tables-only REFRESH (a question, taken unsigned) makes the server publish PARAMS, TIMELINE
/// and the last second's STATUS at once: the first Message on `channel` of Channels within the
/// timeout (that answer, or with nobody to answer the question the once-a-second one) is
/// printed with `print`. Exit code kOk, or kNoAnswer naming `what`.
template <class Message, class Print>
int AwaitAndPrint(const Globals& globals, std::string Channels::*channel, const std::string& what,
                  Print print) {
  Link link(globals);
  std::optional<Message> received;
  SubscribeDecoded<Message>(link.bus, link.channels.*channel, [&received](const Message& message) {
    if (!received) received = message;
  });
  const double start = MonotonicSeconds();
  refresh_request_t question{};
  question.tables_only = true;
  CommandClient(link.bus, link.channels, std::min(globals.timeout, kRefreshAnswerWait), link.signer)
      .Send(link.channels.refresh, question);
  const double left = globals.timeout - (MonotonicSeconds() - start);
  if (!HandleUntil(link.bus, std::max(left, 0.0), [&received] { return received.has_value(); })) {
    return link.NoAnswer(what);
  }
  print(*received);
  return kOk;
}

}  // namespace flagsim
