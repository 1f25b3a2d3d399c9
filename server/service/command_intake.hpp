// Command intake: the server's command channels (WIND, PARAM, CAMERA, KEYFRAME, TIME, DESIGN, REFRESH). Each
// message is decoded from raw bytes with every length checked (wire::CheckedDecode), checked for its
// signature when the server has keys (command_authenticator.hpp), answered on ACK, and applied to the session
// only if valid. Undecodable bytes are counted and dropped; nothing a client sends can stop the server. A
// retry (same client id and sequence) gets the first answer again and is not applied twice.
//
//   bytes => decode => signed, authentic, fresh, new? => retry? => validate and apply => ACK
//
// Refused commands (unsigned, forged, stale, replayed) are counted by kind and change nothing; at
// most kRefusalAnswersPerSecond of them are answered, so that a flood of forgeries costs the server
// little more than their MACs and the bus no more than that many answers a second.
//
// Accepted WIND and PARAM commands are answered kSettleSteps steps later: if the guard had to
// recover the flag in between, the ACK says what it found and did (the command is still
// applied; the reason field carries the note). So does the ACK of a WIND, PARAM or CAMERA
// command that set what a playing timeline drives, which then lasts one step.
#pragma once

#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "flagsim/ack_t.hpp"
#include "flagsim/camera_command_t.hpp"
#include "flagsim/design_piece_t.hpp"
#include "flagsim/keyframe_command_t.hpp"
#include "flagsim/param_command_t.hpp"
#include "flagsim/refresh_request_t.hpp"
#include "flagsim/time_command_t.hpp"
#include "flagsim/wind_command_t.hpp"
#include "messages/bus.hpp"
#include "messages/channels.hpp"
#include "messages/command_key.hpp"
#include "messages/utime.hpp"
#include "server/service/command_authenticator.hpp"
#include "server/service/design_assembly.hpp"
#include "server/service/journal.hpp"
#include "server/service/server_presence.hpp"
#include "server/service/server_stats.hpp"
#include "server/service/session.hpp"

namespace flagsim {

class CommandIntake {
 public:
  static constexpr size_t kMaxCommandBytes = 64 * 1024;
  static constexpr size_t kMaxClientIdLength = 64;
  static constexpr int kQueueCapacity = 256;  ///< per channel, between two Handle() calls

  static constexpr int kRefusalAnswersPerSecond = 50;

  /// Subscribes to the command channels on `bus`; handlers run inside bus.Handle(). With `keys`,
  /// only commands signed with one of them are taken. `clock` (s, monotonic: the server loop's)
  /// paces the answers to refusals and the log lines about drops.
  CommandIntake(Bus& bus, const Channels& channels, Session& session, ServerStats& stats,
                std::vector<CommandKey> keys = {}, std::function<double()> clock = MonotonicSeconds);

  /// True once after any accepted command that changed parameters (PARAMS is due).
  bool TakeParamsChanged() { return std::exchange(params_changed_, false); }
  /// True once after any accepted command that changed the timeline (TIMELINE is due).
  bool TakeTimelineChanged() { return std::exchange(timeline_changed_, false); }
  /// After each step: answers the commands whose settling window has passed.
  void AfterStep();
  /// Answers every command still settling (the server is about to stop).
  void FlushPending();

  static constexpr int kSettleSteps = 32;

  /// Where accepted commands are journaled (APPLIED), if anywhere.
  void SetJournal(Journal* journal) { journal_ = journal; }
  /// Whose id, and how many other servers, every ACK states (server_presence.hpp), if anyone's.
  void SetPresence(const ServerPresence* presence) { presence_ = presence; }

  /// For STATUS: whether and how commands are authenticated.
  std::string Authentication() const { return authenticator_.Describe(); }

  /// Once after REFRESH requests: the latest request id (a full STATE and PARAMS and a
  /// keyframe are due); -1 when none came.
  int64_t TakeRefreshRequest() { return std::exchange(refresh_request_, -1); }
  /// Whether a keyframe request waits to be taken.
  bool RefreshPending() const { return refresh_request_ >= 0; }
  /// True once after tables-only REFRESH requests (PARAMS, TIMELINE and STATUS are due).
  bool TakeTablesRequest() { return std::exchange(tables_request_, false); }

  /// Undecodable bytes heard on `channel` (a command channel, or another that the server reads:
  /// STATUS): counted in STATUS (messages_dropped), the latest logged at most once a second.
  void Drop(const std::string& channel, const std::string& reason);

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
  std::string ApplyKeyframe(const keyframe_command_t& command);
  std::string ApplyTime(const time_command_t& command);
  std::string ApplyDesignPiece(const design_piece_t& piece);

  void Refuse(const std::string& channel, const std::string& client_id, int64_t sequence,
              const CommandAuthenticator::Verdict& verdict);
  void Answer(ack_t ack, int64_t recoveries_before);
  void Stamp(ack_t* ack) const;

  /// An accepted command whose answer waits for the flag to settle under it.
  struct Settling {
    ack_t ack;
    int64_t due_step;
    int64_t recoveries_before;  ///< the guard's count when it was applied
  };

  Bus& bus_;
  const Channels& channels_;
  Session& session_;
  ServerStats& stats_;
  Journal* journal_ = nullptr;
  const ServerPresence* presence_ = nullptr;
  CommandAuthenticator authenticator_;
  std::function<double()> clock_;
  std::map<std::string, ack_t> last_ack_;  ///< per client id: the answer to its latest command
  std::vector<Settling> settling_;         ///< in the order they were applied
  bool params_changed_ = false;
  bool timeline_changed_ = false;
  std::string note_;            ///< for the ACK of the command being applied, if it is accepted
  DesignAssembly designs_;      ///< pieces of design files on their way
  DesignFilePtr design_shown_;  ///< the file the DESIGN piece being applied completed, if it did
  int64_t refresh_request_ = -1;
  bool tables_request_ = false;
  double last_drop_log_ = -INFINITY;  ///< s on the clock: the last logged drop (logged once a second)
  int64_t drops_since_log_ = 0;
  double refusal_second_ = -INFINITY;     ///< s on the clock: when the current second of refusals began
  int64_t refusals_in_second_ = 0;        ///< refusals in it: answered and logged up to the limit
  BusSubscriptions subscriptions_{bus_};  ///< last: dropped first, before what the handlers use
};

}  // namespace flagsim
