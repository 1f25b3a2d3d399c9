#include "client/command_client.hpp"

#include <unistd.h>

#include <cstdio>

namespace flagsim {
namespace {

/// "flagctl-<pid>-<8 random hex digits>": unique enough among a bus's clients.
std::string NewClientId() {
  std::random_device entropy;
  char id[48];
  std::snprintf(id, sizeof(id), "flagctl-%d-%08x", static_cast<int>(getpid()), entropy());
  return id;
}

}  // namespace

CommandOutcome OutcomeOf(const ack_t& ack) {
  CommandOutcome outcome;
  outcome.result = ack.accepted ? CommandOutcome::kAccepted : CommandOutcome::kRejected;
  outcome.reason = ack.reason;
  outcome.step = ack.step;
  outcome.server_id = ack.server_id;
  outcome.other_servers = ack.other_servers;
  return outcome;
}

CommandClient::CommandClient(Bus& bus, const Channels& channels, double timeout_seconds, CommandSigner signer,
                             std::function<double()> clock)
    : bus_(bus),
      timeout_(timeout_seconds),
      signer_(std::move(signer)),
      clock_(std::move(clock)),
      client_id_(NewClientId()) {
  ack_subscription_ = bus_.Subscribe(
      channels.ack, [this](const std::string&, const uint8_t* data, size_t size) { OnAck(data, size); });
}

CommandClient::~CommandClient() { bus_.Unsubscribe(ack_subscription_); }

void CommandClient::OnAck(const uint8_t* data, size_t size) {
  std::string error;
  const auto ack = wire::CheckedDecode<ack_t>(data, size, 64 * 1024, &error);
  if (!ack || ack->client_id != client_id_ || ack->sequence != awaited_) return;  // not ours
  outcome_ = OutcomeOf(*ack);
}

}  // namespace flagsim
