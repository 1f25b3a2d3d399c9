// One flagd as the gateway serves it: its channels on the bus, decoded (checked) into a feed per
// gateway channel (JSON made once, shared by every client), its frames mirrored, its newest
// parameter table, its recorder. The hub (gateway.hpp) owns one per server and feeds it the
// server's STATUS (the hub's subscription is what finds servers):
//
//   TILE, FRAME ==> mirror (hash-checked) ==> tiles, and the camera and JPEG feeds
//   STATE ==> state and scene feeds;  STATUS, TIMELINE ==> their feeds
//   PARAMS ==> params feed, and to the hub the values that changed
//   ACK ==> acks feed, and to the hub for its command relay
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "client/gateway/channel_feed.hpp"
#include "client/gateway/command_relay.hpp"
#include "client/gateway/frame_mirror.hpp"
#include "client/gateway/gateway_catalog.hpp"
#include "client/gateway/session_recorder.hpp"
#include "flagsim/ack_t.hpp"
#include "flagsim/frame_t.hpp"
#include "flagsim/params_t.hpp"
#include "flagsim/status_t.hpp"
#include "messages/bus.hpp"
#include "messages/channels.hpp"

namespace flagsim::gateway {

/// Counters of one server's streams, since the gateway started.
struct ServerLinkCounters {
  uint64_t incomplete_frames = 0;
  uint64_t frames_mirrored = 0;
  uint64_t server_restarts = 0;  ///< a new server id on STATE or STATUS after another one
  int64_t bus_undecodable = 0;   ///< messages on the server's channels that are not their type
};

class ServerLink {
 public:
  static constexpr int kIncompleteBeforeRefresh = 3;  ///< frames in a row the gateway could not complete
  static constexpr double kRefreshInterval = 1.0;     ///< s between the gateway's own keyframe requests
  static constexpr size_t kAcksKept = 64;

  /// What the link tells the hub.
  struct Hooks {
    std::function<void()> wake;  ///< there are new messages: wake every client
    /// The parameters whose values changed ([{name, value}], names as the server has them).
    std::function<void(const nlohmann::json& changed)> parameters_changed;
    std::function<void(const ack_t& ack)> ack;  ///< every ACK, for the hub's command relay
  };

  using RecorderMaker = std::function<std::unique_ptr<SessionRecorder>(const Channels& channels)>;

  /// The server on `prefix`, offered in `slot` under `path`, recorded by what `make_recorder`
  /// makes. Subscribes to its channels but STATUS, which comes through OnStatus.
  ServerLink(Bus& bus, const std::string& prefix, uint32_t slot, std::string path, CommandRelay& relay,
             const RecorderMaker& make_recorder, std::function<double()> clock, Hooks hooks);

  void OnStatus(const status_t& status);
  /// A REFRESH, at most one each kRefreshInterval unless `always` (a recording needs its own:
  /// the answer to an earlier one may have come before it started).
  void RequestKeyframe(bool always = false);
  /// The image feed is kept only while someone subscribes to it.
  void SubscribersChanged(uint32_t base, int delta);

  ChannelFeed& feed(uint32_t base) { return feeds_[base]; }
  std::shared_ptr<const MirroredFrame> frame() const { return mirror_.latest(); }
  const std::optional<params_t>& params() const { return params_; }
  SessionRecorder& recorder() { return *recorder_; }
  const SessionRecorder& recorder() const { return *recorder_; }
  const Channels& channels() const { return channels_; }
  const std::string& path() const { return path_; }
  uint32_t slot() const { return slot_; }
  /// When its last STATUS came, on the clock; -infinity before one.
  double last_heard() const { return last_heard_; }
  const ServerLinkCounters& counters() const { return counters_; }

  /// Its entry in /gateway/servers (schemas/servers.json); `live` as the hub judges it.
  nlohmann::json Summary(bool live, double frames_per_second) const;

 private:
  void Subscribe();
  /// Subscribes `handler` to the valid Messages on `channel`; the rest are counted as undecodable.
  template <class Message>
  void On(const std::string& channel, std::function<void(const Message&)> handler, int capacity = 30);
  void OnFrame(const frame_t& manifest);
  void OnParams(const params_t& params);
  /// The server id of a STATE or STATUS: a new one after another means a new server, whose
  /// frames start again (FrameMirror::ServerRestarted), and a keyframe is asked of it at once.
  void NoteServer(int64_t server_id);
  void Publish(uint32_t base, int64_t utime, std::string payload);

  Channels channels_;
  uint32_t slot_;
  std::string path_;
  CommandRelay& relay_;
  std::unique_ptr<SessionRecorder> recorder_;
  std::function<double()> clock_;
  Hooks hooks_;
  FrameMirror mirror_;
  std::array<ChannelFeed, kServerChannelCount + 1> feeds_;  ///< by base id; [0] unused
  std::array<int, kServerChannelCount + 1> subscribers_{};  ///< clients subscribed, by base id
  std::optional<params_t> params_;                          ///< the newest table
  std::optional<status_t> status_;                          ///< the newest STATUS
  nlohmann::json last_camera_;  ///< the newest camera published, without its frame id
  int incomplete_in_a_row_ = 0;
  int64_t server_id_ = 0;  ///< the server on the bus, 0 before its first STATE or STATUS
  double last_refresh_ = -1e9;
  double last_heard_;
  ServerLinkCounters counters_;
  BusSubscriptions subscriptions_;  ///< last: dropped first, before what the handlers use
};

}  // namespace flagsim::gateway
