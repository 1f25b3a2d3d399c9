// The signature of a command: HMAC-SHA-256 (RFC 2104; FIPS 198-1) under a shared key of
//
//   channel ‖ 0x00 ‖ LCM encoding of the command with its mac field zeroed
//
// LCM's encoding starts with the type's fingerprint and holds every field: the payload, the
// client id, the sequence number, the time stamp (utime) and the key's name. So a signed
// command moved to another channel or type, changed, re-dated or renumbered no longer checks
// out. The server's other checks (fresh, not replayed) are in command_authenticator.hpp.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

#include "messages/command_key.hpp"
#include "messages/utime.hpp"

namespace flagsim {

using Mac = std::array<uint8_t, 32>;

/// HMAC-SHA-256 under `key` of channel ‖ 0x00 ‖ the `size` bytes at `encoded`.
Mac ComputeMac(const CommandKey& key, const std::string& channel, const uint8_t* encoded, size_t size);

/// The MAC `command` should carry on `channel` (its own mac field is not read).
template <class Command>
Mac MacOf(const CommandKey& key, const std::string& channel, Command command) {
  std::fill(std::begin(command.mac), std::end(command.mac), 0);
  std::vector<uint8_t> bytes(static_cast<size_t>(command.getEncodedSize()));
  command.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return ComputeMac(key, channel, bytes.data(), bytes.size());
}

/// Whether `carried` (32 bytes) equals `expected`, in time that does not depend on where they
/// differ.
bool MacMatches(const Mac& expected, const uint8_t* carried);

/// Stamps each command a client sends (and each resend): the time now and, with a key, the
/// key's name and the MAC.
class CommandSigner {
 public:
  CommandSigner() = default;  ///< signs nothing: for servers that take unsigned commands
  explicit CommandSigner(CommandKey key) : key_(std::move(key)) {}

  template <class Command>
  void Stamp(const std::string& channel, Command& command) const {
    command.utime = UnixMicros();
    if (!key_) return;
    command.key_id = key_->name;
    const Mac mac = MacOf(*key_, channel, command);
    std::copy(mac.begin(), mac.end(), std::begin(command.mac));
  }

  bool signs() const { return key_.has_value(); }

 private:
  std::optional<CommandKey> key_;
};

}  // namespace flagsim
