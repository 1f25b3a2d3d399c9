#include "server/service/command_authenticator.hpp"

#include <cstdio>
#include <iterator>

#include "common/printable_text.hpp"

namespace flagsim {
namespace {

constexpr size_t kPruneAbove = 4096;  ///< clients remembered before the stale ones are forgotten

using Refusal = CommandAuthenticator::Refusal;

CommandAuthenticator::Verdict Refuse(Refusal refusal, const std::string& detail) {
  return {refusal, std::string(RefusalName(refusal)) + ": " + detail};
}

std::string Seconds(int64_t micros) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.1f s", static_cast<double>(micros) / 1e6);
  return text;
}

}  // namespace

const char* RefusalName(Refusal refusal) {
  switch (refusal) {
    case Refusal::kNone:
      return "accepted";
    case Refusal::kUnsigned:
      return "unsigned";
    case Refusal::kUnknownKey:
      return "unknown key";
    case Refusal::kBadMac:
      return "bad MAC";
    case Refusal::kStale:
      return "stale";
    case Refusal::kReplayed:
      return "replayed";
  }
  return "?";
}

CommandAuthenticator::CommandAuthenticator(std::vector<CommandKey> keys) : keys_(std::move(keys)) {}

std::string CommandAuthenticator::Describe() const {
  if (!enabled()) return "none: commands are unauthenticated";
  std::string names;
  for (const CommandKey& key : keys_) names += (names.empty() ? "" : ", ") + key.name;
  return "HMAC-SHA-256, keys " + names;
}

const CommandKey* CommandAuthenticator::Find(const std::string& key_id) const {
  for (const CommandKey& key : keys_)
    if (key.name == key_id) return &key;
  return nullptr;
}

CommandAuthenticator::Verdict CommandAuthenticator::Unknown(const std::string& key_id) const {
  if (key_id.empty())
    return Refuse(Refusal::kUnsigned,
                  "this server takes only commands signed with one of its keys "
                  "(flagctl --key-file FILE)");
  return Refuse(Refusal::kUnknownKey,
                "'" + PrintableText(key_id, CommandKey::kMaxNameLength) + "' is none of this server's keys");
}

CommandAuthenticator::Verdict CommandAuthenticator::BadMac(const std::string& key_id) const {
  return Refuse(Refusal::kBadMac, "the MAC does not match key '" + key_id +
                                      "': signed with another key, or changed on the way");
}

CommandAuthenticator::Verdict CommandAuthenticator::CheckFreshAndNew(const std::string& key_id,
                                                                     const std::string& client_id,
                                                                     int64_t sequence, int64_t utime,
                                                                     int64_t now_utime) {
  // |utime - now|, without overflow for any utime a sender may claim.
  const bool ahead = utime > now_utime;
  const uint64_t apart =
      ahead ? uint64_t(utime) - uint64_t(now_utime) : uint64_t(now_utime) - uint64_t(utime);
  if (apart > uint64_t(kFreshnessMicros)) {
    const std::string how_far = apart > uint64_t(1e15) ? "years" : Seconds(static_cast<int64_t>(apart));
    return Refuse(Refusal::kStale, "its time stamp is " + how_far + (ahead ? " ahead of" : " behind") +
                                       " the server's clock; allowed within " + Seconds(kFreshnessMicros));
  }
  const std::pair<std::string, std::string> client{key_id, client_id};
  const auto last = seen_.find(client);
  if (last != seen_.end()) {
    const Seen& seen = last->second;
    if (sequence < seen.sequence)
      return Refuse(Refusal::kReplayed, "sequence " + std::to_string(sequence) + " from " +
                                            PrintableText(client_id) + ", which has already sent " +
                                            std::to_string(seen.sequence));
    if (sequence == seen.sequence && utime <= seen.utime)
      return Refuse(Refusal::kReplayed, "sequence " + std::to_string(sequence) + " from " +
                                            PrintableText(client_id) + " with a time stamp already seen");
  }
  seen_[client] = {sequence, utime};
  if (seen_.size() > kPruneAbove) Prune(now_utime);
  return {};
}

void CommandAuthenticator::Prune(int64_t now_utime) {
  for (auto entry = seen_.begin(); entry != seen_.end();) {
    const bool stale = now_utime - entry->second.utime > kFreshnessMicros;
    entry = stale ? seen_.erase(entry) : std::next(entry);
  }
}

}  // namespace flagsim
