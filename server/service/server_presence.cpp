#include "server/service/server_presence.hpp"

#include <spdlog/spdlog.h>

#include <random>

#include "flagsim/status_t.hpp"
#include "messages/checked_decode.hpp"

namespace flagsim {
namespace {

int64_t NewServerId() {
  std::random_device entropy;
  const uint64_t bits = (uint64_t(entropy()) << 32) | entropy();
  const auto id = static_cast<int64_t>(bits >> 1);  // positive
  return id != 0 ? id : 1;
}

}  // namespace

ServerPresence::ServerPresence(Bus& bus, const Channels& channels, std::function<double()> clock,
                               DropSink dropped)
    : clock_(std::move(clock)),
      dropped_(std::move(dropped)),
      channel_(channels.status),
      prefix_(channels.prefix),
      id_(NewServerId()),
      subscriptions_(bus) {
  subscriptions_.Subscribe(channels.status,
                [this](const std::string&, const uint8_t* data, size_t size) { OnStatus(data, size); });
}

int ServerPresence::others() const {
  const double now = clock_();
  int count = 0;
  for (const auto& [id, when] : heard_) count += now - when <= kForgetAfter;
  return count;
}

void ServerPresence::OnStatus(const uint8_t* data, size_t size) {
  std::string error;
  const auto status = wire::CheckedDecode<status_t>(data, size, 64 * 1024, &error);
  if (!status) {
    if (dropped_) dropped_(channel_, error);
    return;
  }
  if (status->server_id == id_ || status->server_id == 0) return;  // ours, or not a server's
  const double now = clock_();
  for (auto it = heard_.begin(); it != heard_.end();) {  // forget those gone quiet
    it = now - it->second > kForgetAfter ? heard_.erase(it) : std::next(it);
  }
  const bool known = heard_.count(status->server_id) > 0;
  if (!known && heard_.size() >= kMaxRemembered) return;
  heard_[status->server_id] = now;
  if (known) return;
  spdlog::error(
      "another server (id {:016x}) publishes on prefix '{}': it takes every command as this one "
      "(id {:016x}) does, and their STATE and frames interleave; stop one, or give each its own --prefix",
      status->server_id, prefix_, id_);
}

}  // namespace flagsim
