#include "messages/channels.hpp"

namespace flagsim {

Channels::Channels(const std::string& prefix_in)
    : prefix(prefix_in),
      wind(prefix + "WIND"),
      param(prefix + "PARAM"),
      camera(prefix + "CAMERA"),
      keyframe(prefix + "KEYFRAME"),
      refresh(prefix + "REFRESH"),
      ack(prefix + "ACK"),
      state(prefix + "STATE"),
      tile(prefix + "TILE"),
      frame(prefix + "FRAME"),
      params(prefix + "PARAMS"),
      status(prefix + "STATUS"),
      timeline(prefix + "TIMELINE"),
      applied(prefix + "APPLIED"),
      checkpoint(prefix + "CHECKPOINT") {}

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
