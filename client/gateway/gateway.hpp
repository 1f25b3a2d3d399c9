// The gateway's hub: one bus client (flagctl serve) shared by every browser and Foxglove
// client connected to it, serving one flagd or several. Everything runs on one event loop: the
// bus's messages, the clients' requests and their writes, so nothing here locks.
//
//   bus STATUS ==> the server's link (found, or made for a server newly heard) ==> advertised
//   bus ==> links (server_link.hpp: feeds, frame mirror) ==> Wake() every client, whose
//           protocol takes what it has not had
//   client request ==> the service's server ==> command (command_services.hpp) ==> relay
//           (resent until its ACK) ==> the answer to that client
//   a server silent for kSilence (of several) ==> withdrawn from every client
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "client/gateway/channel_feed.hpp"
#include "client/gateway/client_hub.hpp"
#include "client/gateway/client_protocol.hpp"
#include "client/gateway/command_relay.hpp"
#include "client/gateway/command_services.hpp"
#include "client/gateway/design_uploads.hpp"
#include "client/gateway/recording_exports.hpp"
#include "client/gateway/server_link.hpp"
#include "flagsim/status_t.hpp"
#include "messages/bus.hpp"
#include "messages/channels.hpp"
#include "messages/command_mac.hpp"
#include "messages/utime.hpp"

namespace flagsim::gateway {

/// Which servers a gateway serves.
struct ServerSelection {
  /// One server, on `prefix`, with plain topics (/flag/tiles), offered from the start.
  static ServerSelection One(const std::string& prefix);
  /// Each server heard on the bus whose prefix is in `prefixes` (every one, if empty), with its
  /// topics, services and parameters under /PREFIX, offered while it is heard.
  static ServerSelection Many(std::vector<std::string> prefixes);

  bool many = false;
  std::vector<std::string> prefixes;  ///< One: the one; Many: those wanted (all if empty)
};

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

/// Counters of refusals and drops, since start; the transport counts its own, the links theirs.
struct GatewayCounters {
  uint64_t unauthorized = 0;     ///< 401
  uint64_t forbidden = 0;        ///< 403
  uint64_t protocol_errors = 0;  ///< client messages that were not the protocol
  uint64_t clients_dropped = 0;  ///< for not reading, or a queue overflowing
  uint64_t servers_ignored = 0;  ///< STATUS of servers beyond kMaxServers
};

class Gateway : public ClientHub {
 public:
  static constexpr int kMaxCommandsInFlight = 32;  ///< per client: commands sent and not yet answered
  static constexpr size_t kMaxServers = 32;        ///< servers one gateway serves
  static constexpr double kSilence = 5.0;          ///< s without its STATUS: one of several has gone

  Gateway(Bus& bus, ServerSelection servers, GatewayOptions options);

  /// Resends commands, times them out, withdraws silent servers, publishes /gateway/status and
  /// /gateway/servers each second.
  void Tick();
  /// When Tick is next needed, on the clock.
  double NextDue() const;

  int Attach(GatewayClient* client);
  void Detach(int client);
  size_t clients() const { return clients_.size(); }

  // ClientHub: what clients' protocols use.
  std::vector<std::string> Advertisements() const override;
  ChannelKind KindOf(uint32_t id) const override;
  ChannelFeed* Feed(uint32_t id) override;
  std::shared_ptr<const MirroredFrame> Frame(uint32_t id) const override;
  std::optional<uint32_t> ServiceForTopic(std::string_view topic) const override;
  void SubscribersChanged(uint32_t id, int delta) override;
  void CallService(int client, uint32_t service, uint32_t call, std::string_view encoding,
                   std::string_view payload) override;
  void PublishCommand(int client, uint32_t service, std::string_view payload) override;
  void GetParameters(int client, const nlohmann::json& names, const std::string& id) override;
  void SetParameters(int client, const nlohmann::json& parameters, const std::string& id) override;
  void CountProtocolError() override { ++counters_.protocol_errors; }

  /// The single server's newest whole frame (slot 0).
  std::shared_ptr<const MirroredFrame> frame() const { return Frame(kTilesChannel); }
  /// The server in `slot`; nullptr if none was heard there.
  const ServerLink* server(uint32_t slot) const;
  GatewayCounters& counters() { return counters_; }
  /// A finished recording's path, for the HTTP side; nullopt if `name` is none.
  std::optional<std::string> RecordingFile(std::string_view name) const;
  const GatewayOptions& options() const { return options_; }

 private:
  using Reply = std::function<void(ClientProtocol&, const nlohmann::json&)>;
  using Fail = std::function<void(const std::string&)>;

  void OnStatus(const std::string& channel, const status_t& status);
  /// The link of `prefix`, made (in the next slot) if this gateway serves it and has room.
  ServerLink* LinkFor(const std::string& prefix);
  /// The link in `slot` if it is offered now; else nullptr.
  ServerLink* LiveLink(uint32_t slot) const;
  void Offer(ServerLink& link);
  void Withdraw(ServerLink& link);
  void WakeAll();
  void RecordingEnded(const ServerLink& link, const std::string& why);
  void PublishGatewayStatus(double now);
  void PublishServers();
  /// The server a setParameters message is for; nullptr with *problem set if none.
  ServerLink* ParametersServer(const nlohmann::json& parameters, std::string* problem) const;

  /// Sends `command` on `channel` and answers `client` with `reply(result JSON)` when its ACK
  /// comes or the timeout passes (nothing if the client has gone). The one place the in-flight
  /// limit is held: beyond it, `fail` says so and nothing is sent. True if sent.
  bool Relay(int client, const ServerLink& link, const std::string& channel, const Command& command,
             Reply reply, Fail fail);
  ClientProtocol* Client(int id);
  void ServiceRequest(int client, ServerLink& link, uint32_t base, const nlohmann::json& request, Reply reply,
                      Fail fail);
  /// /flag/design (design_uploads.hpp): a built-in design, or a part of a person's image, whose
  /// last part sends the whole in DESIGN pieces.
  void DesignRequest(int client, ServerLink& link, const nlohmann::json& request, Reply reply, Fail fail);
  void RelayPieces(int client, ServerLink& link, std::shared_ptr<const std::vector<design_piece_t>> pieces,
                   size_t index, Reply reply);

  Bus& bus_;
  ServerSelection selection_;
  GatewayOptions options_;
  CommandRelay relay_;
  std::map<uint32_t, std::unique_ptr<ServerLink>> links_;  ///< by slot; kept while the gateway runs
  std::map<std::string, uint32_t> slots_;                  ///< by prefix
  std::set<uint32_t> offered_;                             ///< slots whose server is advertised now
  std::map<uint32_t, std::pair<nlohmann::json, nlohmann::json>> offers_;  ///< by slot: channels, services
  ChannelFeed status_feed_, servers_feed_;                                ///< the gateway's own channels
  std::map<int, GatewayClient*> clients_;
  std::map<int, int> commands_in_flight_;  ///< by client
  DesignUploads uploads_;                  ///< images coming from clients, in parts
  int next_client_ = 1;
  double next_status_ = 0;
  double status_window_start_ = 0;
  std::map<int, ClientCounters> counters_at_window_;
  std::map<uint32_t, uint64_t> frames_at_window_;  ///< by slot
  std::map<uint32_t, double> frames_per_second_;   ///< by slot, over the last window
  double started_ = 0;
  GatewayCounters counters_;
  BusSubscriptions subscriptions_;  ///< last: dropped first, before what the handlers use
};

}  // namespace flagsim::gateway
