// The gateway's hub: one bus client (flagctl serve) shared by every browser and Foxglove
// client connected to it. Everything runs on one event loop: the bus's messages, the clients'
// requests and their writes, so nothing here locks.
//
//   bus ==> decode (checked) ==> feeds (one per channel: JSON made once, shared) and the frame
//           mirror ==> Wake() every client, whose protocol takes what it has not had
//   client request ==> command (WIND, PARAM, ...) ==> relay (resent until its ACK) ==> the
//           answer to that client: a service response, parameter values, a status
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>

#include "client/gateway/channel_feed.hpp"
#include "client/gateway/client_protocol.hpp"
#include "client/gateway/command_relay.hpp"
#include "client/gateway/design_uploads.hpp"
#include "client/gateway/frame_mirror.hpp"
#include "client/gateway/gateway_catalog.hpp"
#include "client/gateway/session_recorder.hpp"
#include "flagsim/design_piece_t.hpp"
#include "flagsim/params_t.hpp"
#include "messages/bus.hpp"
#include "messages/channels.hpp"
#include "messages/command_mac.hpp"
#include "messages/utime.hpp"

namespace flagsim::gateway {

struct GatewayOptions {
  std::string name = "flagsim";  ///< serverInfo's name
  double command_timeout = 2.0;  ///< s to wait for a command's ACK
  std::string record_directory = "recordings";
  std::function<double()> clock = MonotonicSeconds;  ///< s, monotonic; tests drive their own
  CommandSigner signer;  ///< signs the commands it relays, for a server with keys (flagctl --key-file)
  /// Makes a video of a finished recording (flagctl export's MP4), if given; MCAP is made always.
  RecordingExports::Exporter video_exporter;
};

/// A connected client as the gateway sees it; the transport implements it.
class GatewayClient {
 public:
  virtual ~GatewayClient() = default;
  virtual ClientProtocol& protocol() = 0;
  /// There may be something new to send: write it when the socket is free.
  virtual void Wake() = 0;
  virtual std::string address() const = 0;
};

/// Counters of refusals and drops, since start; the transport counts its own.
struct GatewayCounters {
  uint64_t unauthorized = 0;     ///< 401
  uint64_t forbidden = 0;        ///< 403
  uint64_t protocol_errors = 0;  ///< client messages that were not the protocol
  uint64_t clients_dropped = 0;  ///< for not reading, or a queue overflowing
  uint64_t incomplete_frames = 0;
  uint64_t frames_mirrored = 0;
  uint64_t server_restarts = 0;  ///< a new server id on STATE or STATUS after another one
  int64_t bus_undecodable = 0;   ///< messages on the server's channels that are not their type
};

class Gateway {
 public:
  static constexpr int kIncompleteBeforeRefresh = 3;  ///< frames in a row the gateway could not complete
  static constexpr double kRefreshInterval = 1.0;     ///< s between the gateway's own keyframe requests
  static constexpr size_t kAcksKept = 64;
  static constexpr int kMaxCommandsInFlight = 32;  ///< per client: commands sent and not yet answered

  Gateway(Bus& bus, const Channels& channels, GatewayOptions options);

  /// Resends commands, times them out, publishes /gateway/status each second.
  void Tick();
  /// When Tick is next needed, on the clock.
  double NextDue() const;

  int Attach(GatewayClient* client);
  void Detach(int client);
  size_t clients() const { return clients_.size(); }

  // What clients' protocols use.
  ChannelFeed& feed(uint32_t channel) { return feeds_[channel]; }
  std::shared_ptr<const MirroredFrame> frame() const { return mirror_.latest(); }
  void SubscribersChanged(uint32_t channel, int delta);
  void CallService(int client, uint32_t service, uint32_t call, std::string_view encoding,
                   std::string_view payload);
  void PublishCommand(int client, uint32_t service, std::string_view payload);
  void GetParameters(int client, const nlohmann::json& names, const std::string& id);
  void SetParameters(int client, const nlohmann::json& parameters, const std::string& id);

  GatewayCounters& counters() { return counters_; }
  /// A finished recording's path, for the HTTP side; nullopt if `name` is none.
  std::optional<std::string> RecordingFile(std::string_view name) const {
    return recorder_.FinishedFile(name);
  }
  const GatewayOptions& options() const { return options_; }

 private:
  void SubscribeBus();
  void OnFrame(const frame_t& manifest);
  void OnParams(const params_t& params);
  void OnAck(const ack_t& ack);
  /// The server id of a STATE or STATUS: a new one after another means a new server, whose
  /// frames start again (FrameMirror::ServerRestarted), and a keyframe is asked of it at once.
  void NoteServer(int64_t server_id);
  void Publish(uint32_t channel, int64_t utime, std::string payload);
  void WakeAll();
  void RecordingEnded(const std::string& why);
  /// A REFRESH, at most one each kRefreshInterval unless `always` (a recording needs its own:
  /// the answer to an earlier one may have come before it started).
  void RequestKeyframe(bool always = false);
  void PublishGatewayStatus(double now);

  /// Sends `command` on `channel` and answers `client` with `reply(result JSON)` when its ACK
  /// comes or the timeout passes; nothing if the client has gone.
  template <class Command>
  void Relay(int client, const std::string& channel, const Command& command,
             std::function<void(ClientProtocol&, const nlohmann::json&)> reply);
  ClientProtocol* Client(int id);
  void ServiceRequest(int client, uint32_t service, const nlohmann::json& request,
                      std::function<void(ClientProtocol&, const nlohmann::json&)> reply,
                      std::function<void(const std::string&)> fail);
  /// /flag/design (design_uploads.hpp): a built-in design, or a part of a person's image, whose
  /// last part sends the whole in DESIGN pieces.
  void DesignRequest(int client, const nlohmann::json& request,
                     std::function<void(ClientProtocol&, const nlohmann::json&)> reply,
                     std::function<void(const std::string&)> fail);
  void RelayPieces(int client, std::shared_ptr<const std::vector<design_piece_t>> pieces, size_t index,
                   std::function<void(ClientProtocol&, const nlohmann::json&)> reply);

  Bus& bus_;
  const Channels& channels_;
  GatewayOptions options_;
  CommandRelay relay_;
  SessionRecorder recorder_;
  FrameMirror mirror_;
  std::array<ChannelFeed, kChannelCount + 1> feeds_;  ///< by channel id; [0] unused
  std::array<int, kChannelCount + 1> subscribers_{};  ///< clients subscribed, by channel id
  std::map<int, GatewayClient*> clients_;
  std::map<int, int> commands_in_flight_;  ///< by client
  DesignUploads uploads_;                  ///< images coming from clients, in parts
  int next_client_ = 1;
  std::optional<params_t> params_;  ///< the newest table
  nlohmann::json last_camera_;      ///< the newest camera published, without its frame id
  int incomplete_in_a_row_ = 0;
  int64_t server_id_ = 0;  ///< the server on the bus, 0 before its first STATE or STATUS
  double last_refresh_ = -1e9;
  double next_status_ = 0;
  double status_window_start_ = 0;
  std::map<int, ClientCounters> counters_at_window_;
  uint64_t frames_at_window_ = 0;
  double started_ = 0;
  GatewayCounters counters_;
};

}  // namespace flagsim::gateway
