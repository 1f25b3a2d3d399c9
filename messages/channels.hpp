// Channel names: a prefix (default "FLAGSIM_", so several servers can share a bus) plus a name.
#pragma once

#include <cstddef>
#include <string>

namespace flagsim {

struct Channels {
  static constexpr const char* kDefaultPrefix = "FLAGSIM_";
  /// Characters of a prefix, at most: with the longest name (DESIGN_FILE, 11) within the 63 of
  /// an LCM channel name (LCM_MAX_CHANNEL_NAME_LENGTH).
  static constexpr size_t kMaxPrefixLength = 52;

  /// "" if `prefix` makes valid channel names: 1 .. kMaxPrefixLength letters, digits and '_';
  /// else what is wrong and what is allowed. (An empty prefix would make the recorders take every
  /// channel on the bus.)
  static std::string CheckPrefix(const std::string& prefix);
  /// A prefix of its own for a server among many started alike (replicas): the default prefix and
  /// six random hex digits, e.g. "FLAGSIM_3F9A2C_". Two of 100 servers share one with a chance of
  /// about 3 in 10000 (the birthday bound over 2^24); a server that does is told (ServerPresence).
  static std::string RandomPrefix();

  explicit Channels(const std::string& prefix = kDefaultPrefix);

  std::string prefix;
  // client -> server
  std::string wind;      ///< wind_command_t
  std::string param;     ///< param_command_t
  std::string camera;    ///< camera_command_t
  std::string keyframe;  ///< keyframe_command_t
  std::string refresh;   ///< refresh_request_t
  std::string time;      ///< time_command_t
  std::string design;    ///< design_piece_t: a person's image, in pieces
  // server -> clients
  std::string ack;       ///< ack_t
  std::string state;     ///< state_t
  std::string tile;      ///< tile_t
  std::string frame;     ///< frame_t
  std::string params;    ///< params_t
  std::string status;    ///< status_t
  std::string timeline;  ///< timeline_t
  // server -> clients, for replay
  std::string applied;      ///< applied_command_t
  std::string model;        ///< model_t: auto's decisions, journaled in APPLIED only
  std::string checkpoint;   ///< checkpoint_t
  std::string design_file;  ///< design_piece_t: the design's image in force, for replay

  /// "FLAGSIM_WIND" -> "WIND"; a channel without the prefix comes back unchanged.
  std::string Unprefixed(const std::string& channel) const;
  /// A regular expression (LCM subscribe syntax) matching every channel with the prefix.
  std::string AllChannels() const;
};

}  // namespace flagsim
