// Command intake: the server's command channels. Each message is decoded from raw bytes with
// every length checked (wire::CheckedDecode), answered on ACK, and applied to the session only
// if valid. Undecodable bytes are counted and dropped; nothing a client sends can stop the
// server. A retry (same client id and sequence) gets the first answer again and is not
// applied twice.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <utility>

#include "bus.hpp"
#include "channels.hpp"
#include "flagsim/ack_t.hpp"
#include "flagsim/camera_command_t.hpp"
#include "flagsim/param_command_t.hpp"
#include "flagsim/refresh_request_t.hpp"
#include "flagsim/wind_command_t.hpp"
#include "server_stats.hpp"
#include "session.hpp"

namespace flagsim {

class CommandIntake {
 public:
  static constexpr size_t kMaxCommandBytes = 64 * 1024;
  static constexpr size_t kMaxClientIdLength = 64;
  static constexpr int kQueueCapacity = 256;  ///< per channel, between two Handle() calls

  /// Subscribes to the command channels on `bus`; handlers run inside bus.Handle().
  CommandIntake(Bus& bus, const Channels& channels, Session& session, ServerStats& stats);

  /// True once after any accepted command that changed parameters (PARAMS is due).
  bool TakeParamsChanged() { return std::exchange(params_changed_, false); }
  /// Once after REFRESH requests: the latest request id (a full STATE and PARAMS and a
  /// keyframe are due); -1 when none came.
  int64_t TakeRefreshRequest() { return std::exchange(refresh_request_, -1); }

 private:
  template <class Command>
  void Subscribe(const std::string& channel, std::string (CommandIntake::*apply)(const Command&));
  template <class Command>
  void OnMessage(const std::string& channel, const uint8_t* data, size_t size,
                 std::string (CommandIntake::*apply)(const Command&));

  std::string ApplyWind(const wind_command_t& command);
  std::string ApplyParams(const param_command_t& command);
  std::string ApplyRefresh(const refresh_request_t& command);
  std::string ApplyCamera(const camera_command_t& command);

  void Drop(const std::string& channel, const std::string& reason);

  Bus& bus_;
  const Channels& channels_;
  Session& session_;
  ServerStats& stats_;
  std::map<std::string, ack_t> last_ack_;  ///< per client id: the answer to its latest command
  bool params_changed_ = false;
  int64_t refresh_request_ = -1;
  double last_drop_log_ = -1;  ///< wall s of the last logged drop (drops are logged once a second)
  int64_t drops_since_log_ = 0;
};

}  // namespace flagsim
