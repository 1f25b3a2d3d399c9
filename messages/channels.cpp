#include "messages/channels.hpp"

#include <cstdio>
#include <random>

#include "common/printable_text.hpp"

namespace flagsim {

Channels::Channels(const std::string& prefix_in)
    : prefix(prefix_in),
      wind(prefix + "WIND"),
      param(prefix + "PARAM"),
      camera(prefix + "CAMERA"),
      keyframe(prefix + "KEYFRAME"),
      refresh(prefix + "REFRESH"),
      time(prefix + "TIME"),
      design(prefix + "DESIGN"),
      ack(prefix + "ACK"),
      state(prefix + "STATE"),
      tile(prefix + "TILE"),
      frame(prefix + "FRAME"),
      params(prefix + "PARAMS"),
      status(prefix + "STATUS"),
      timeline(prefix + "TIMELINE"),
      applied(prefix + "APPLIED"),
      model(prefix + "MODEL"),
      checkpoint(prefix + "CHECKPOINT"),
      design_file(prefix + "DESIGN_FILE") {}

std::string Channels::CheckPrefix(const std::string& prefix) {
  const std::string allowed = "allowed 1 .. " + std::to_string(kMaxPrefixLength) + " letters, digits and '_'";
  const std::string quoted = "'" + PrintableText(prefix) + "'";
  if (prefix.empty() || prefix.size() > kMaxPrefixLength)
    return quoted + " is " + std::to_string(prefix.size()) + " characters; " + allowed;
  for (const char c : prefix) {
    const bool letter = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z');
    if (!letter && !(c >= '0' && c <= '9') && c != '_')
      return quoted + " is not a channel prefix; " + allowed;
  }
  return "";
}

std::string Channels::RandomPrefix() {
  std::random_device entropy;
  char digits[8];
  std::snprintf(digits, sizeof(digits), "%06X", unsigned(entropy() & 0xFFFFFF));
  return std::string(kDefaultPrefix) + digits + "_";
}

std::string Channels::Unprefixed(const std::string& channel) const {
  return channel.compare(0, prefix.size(), prefix) == 0 ? channel.substr(prefix.size()) : channel;
}

std::string Channels::AllChannels() const {
  std::string escaped;  // LCM channels are POSIX regular expressions
  for (const char c : prefix) {
    if (std::string("\\^$.|?*+()[]{}").find(c) != std::string::npos) escaped += '\\';
    escaped += c;
  }
  return escaped + ".*";
}

}  // namespace flagsim
