#include "client/flagctl_link.hpp"

#include <cstdio>

#include "common/printable_text.hpp"
#include "messages/command_key.hpp"

namespace flagsim {

namespace {

CommandSigner SignerOf(const Globals& globals) {
  if (globals.key_file.empty()) return {};
  return CommandSigner(ReadKeyFile(globals.key_file).front());
}

}  // namespace

Link::Link(const Globals& globals)
    : bus(Bus::WithReceiveBuffer(globals.lcm_url, 8 << 20)),
      channels(globals.prefix),
      globals(globals),
      signer(SignerOf(globals)) {}

int Link::NoAnswer(const std::string& what) const {
  std::fprintf(stderr, "flagctl: no %s from a server with prefix %s on %s within %g s\n", what.c_str(),
               channels.prefix.c_str(), bus.url().c_str(), globals.timeout);
  return kNoAnswer;
}

int Report(const Link& link, const CommandOutcome& outcome) {
  if (outcome.other_servers > 0) {
    std::fprintf(stderr,
                 "flagctl: warning: the server that answered (id %016llx) hears %d other server(s) on prefix "
                 "%s: each takes this command too, and their streams interleave\n",
                 static_cast<unsigned long long>(outcome.server_id), outcome.other_servers,
                 link.channels.prefix.c_str());
  }
  switch (outcome.result) {
    case CommandOutcome::kAccepted:
      std::printf("accepted at step %lld\n", static_cast<long long>(outcome.step));
      if (!outcome.reason.empty()) std::printf("note: %s\n", TerminalText(outcome.reason).c_str());
      return kOk;
    case CommandOutcome::kRejected:
      std::fprintf(stderr, "flagctl: rejected: %s\n", TerminalText(outcome.reason).c_str());
      return kRejected;
    case CommandOutcome::kNoAnswer:
      break;
  }
  return link.NoAnswer("answer");
}

}  // namespace flagsim
