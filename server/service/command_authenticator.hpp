// Who may steer the server. Without keys every command passes, as LCM itself has no notion of
// a sender, and STATUS says that commands are unauthenticated. With keys (flagd --key-file) a
// command passes only if it is
//
//   signed      key_id names one of the server's keys           else kUnsigned, kUnknownKey
//   authentic   its MAC checks out (command_mac.hpp)             else kBadMac
//   fresh       |utime - now| <= kFreshness                      else kStale
//   new         (sequence, utime) after its client's last one    else kReplayed
//
// in that order; nothing of a refused command is remembered. A client resends a command with
// the same sequence and a new utime until it is answered, so a retry passes (the intake answers
// it again and applies it once), while a command captured from the bus and sent again carries a
// utime already seen, or a sequence its client has gone past. Each client (key, client id) is
// remembered while its last command could still be fresh: an older one is refused as stale
// anyway.
//
// Known limit: the memory lives as long as the server. A command captured less than kFreshness
// before a restart can be replayed once to the new server within that time.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "messages/command_key.hpp"
#include "messages/command_mac.hpp"

namespace flagsim {

class CommandAuthenticator {
 public:
  enum class Refusal { kNone, kUnsigned, kUnknownKey, kBadMac, kStale, kReplayed };
  static constexpr int kRefusalKinds = 6;
  static constexpr int64_t kFreshnessMicros = 30'000'000;  ///< utime within 30 s of the server's clock

  struct Verdict {
    Refusal refusal = Refusal::kNone;
    std::string reason;  ///< when refused: the kind first ("bad MAC: ..."), then the detail
  };

  /// No keys: every command passes.
  explicit CommandAuthenticator(std::vector<CommandKey> keys = {});

  bool enabled() const { return !keys_.empty(); }
  /// For STATUS: "none: commands are unauthenticated" or the MAC and the keys' names.
  std::string Describe() const;

  /// Whether `command`, received on `channel` at `now_utime` (µs since the Unix epoch), passes.
  template <class Command>
  Verdict Check(const std::string& channel, const Command& command, int64_t now_utime) {
    if (!enabled()) return {};
    const CommandKey* key = Find(command.key_id);
    if (key == nullptr) return Unknown(command.key_id);
    if (!MacMatches(MacOf(*key, channel, command), command.mac)) return BadMac(command.key_id);
    return CheckFreshAndNew(command.key_id, command.client_id, command.sequence, command.utime, now_utime);
  }

 private:
  /// The last command that passed from one client.
  struct Seen {
    int64_t sequence = 0;
    int64_t utime = 0;
  };

  const CommandKey* Find(const std::string& key_id) const;
  Verdict Unknown(const std::string& key_id) const;
  Verdict BadMac(const std::string& key_id) const;
  Verdict CheckFreshAndNew(const std::string& key_id, const std::string& client_id, int64_t sequence,
                           int64_t utime, int64_t now_utime);
  /// Forgets the clients whose last command is no longer fresh, when there are many.
  void Prune(int64_t now_utime);

  std::vector<CommandKey> keys_;
  std::map<std::pair<std::string, std::string>, Seen> seen_;  ///< by (key name, client id)
};

/// "unsigned", "unknown key", ...: how STATUS and the logs name a refusal.
const char* RefusalName(CommandAuthenticator::Refusal refusal);

}  // namespace flagsim
