#include "client/gateway/command_relay.hpp"

#include <unistd.h>

#include <cstdio>
#include <limits>
#include <random>
#include <vector>

namespace flagsim::gateway {

std::string NewGatewayClientId() {
  std::random_device entropy;
  char id[48];
  std::snprintf(id, sizeof(id), "flagctl-serve-%d-%08x", static_cast<int>(getpid()), entropy());
  return id;
}

CommandRelay::CommandRelay(Bus& bus, std::string client_id, double timeout, CommandSigner signer)
    : bus_(bus), client_id_(std::move(client_id)), timeout_(timeout), signer_(std::move(signer)) {}

void CommandRelay::OnAck(const ack_t& ack) {
  if (ack.client_id != client_id_) return;
  const auto found = pending_.find(ack.sequence);
  if (found == pending_.end()) return;  // answered already, or timed out
  const CommandOutcome outcome = OutcomeOf(ack);
  const Done done = std::move(found->second.done);
  pending_.erase(found);
  done(outcome, ack.sequence);
}

void CommandRelay::Tick(double now) {
  std::vector<std::pair<int64_t, Done>> expired;
  for (auto it = pending_.begin(); it != pending_.end();) {
    if (now >= it->second.deadline) {
      expired.emplace_back(it->first, std::move(it->second.done));
      it = pending_.erase(it);
      continue;
    }
    if (now >= it->second.next_send) {
      it->second.publish();
      it->second.next_send = now + kRetryInterval;
    }
    ++it;
  }
  for (auto& [sequence, done] : expired) done(CommandOutcome{}, sequence);  // kNoAnswer
}

double CommandRelay::NextDue() const {
  double due = std::numeric_limits<double>::infinity();
  for (const auto& [sequence, pending] : pending_) due = std::min({due, pending.deadline, pending.next_send});
  return due;
}

}  // namespace flagsim::gateway
