// One client's side of the Foxglove WebSocket protocol, without the socket: it reads the
// client's messages (subscribe, advertise, parameters, service calls, client publishes) and
// decides what to write next. The transport (websocket_session) calls Next() whenever its one
// write completes, so a client is never sent more than it reads:
//
//   control  serverInfo, advertisements, statuses, parameter values, service responses: in
//            order, at most kMaxControlBytes waiting (beyond that the client is dropped)
//   data     per subscription the newest message it has not had (ChannelFeed), round robin;
//            the picture as the tiles that take this client to the newest frame
#pragma once

#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "client/gateway/client_hub.hpp"
#include "client/gateway/frame_mirror.hpp"

namespace flagsim::gateway {

/// One WebSocket message to write: `head` (small, this client's own) then `body` (shared).
struct Outgoing {
  bool binary = false;
  std::string head;
  std::shared_ptr<const std::string> body;
  size_t size() const { return head.size() + (body ? body->size() : 0); }
};

/// Counters of one client, for /gateway/status.
struct ClientCounters {
  uint64_t bytes_sent = 0;
  uint64_t frames_sent = 0;
  uint64_t frames_skipped = 0;  ///< whole frames that a newer one replaced before this client took them
};

class ClientProtocol {
 public:
  static constexpr size_t kMaxControlBytes = 4 << 20;
  static constexpr size_t kMaxClientChannels = 32;
  static constexpr size_t kMaxFollowedParameters = 64;   ///< names a client follows (the table has fewer)
  static constexpr size_t kMaxParameterNameLength = 64;  ///< characters of a followed name

  ClientProtocol(ClientHub& hub, int client_id);
  /// Tells the gateway its subscriptions are gone (it keeps images only while someone watches).
  ~ClientProtocol();
  ClientProtocol(const ClientProtocol&) = delete;
  ClientProtocol& operator=(const ClientProtocol&) = delete;

  /// The greeting: serverInfo, then the hub's advertisements.
  void Start(const std::string& server_name, const std::string& session_id);
  void OnText(std::string_view text);
  void OnBinary(std::string_view bytes);

  /// What to write next; nullopt when there is nothing.
  std::optional<Outgoing> Next();

  // For the gateway: answers and notices queued on the control path.
  void SendJson(const nlohmann::json& message);
  void SendBinary(std::string frame);
  void SendStatus(int level, const std::string& message, const std::string& id = "");
  /// parameterValues for the parameters among `values` ([{name, value}]) this client follows.
  void OnParametersChanged(const nlohmann::json& values);
  /// The next tile update on `tiles_channel` is a keyframe (after /flag/refresh).
  void ResetTiles(uint32_t tiles_channel) { tiles_[tiles_channel].Reset(); }
  /// A server that came: its advertisements.
  void Announce(const std::vector<std::string>& advertisements);
  /// A server that went: unadvertises its channels and services, and forgets this client's
  /// subscriptions to them and the topics it advertised to publish on them.
  void Withdraw(const std::vector<uint32_t>& channels, const std::vector<uint32_t>& services);

  bool overflowed() const { return overflowed_; }
  int id() const { return client_id_; }
  const ClientCounters& counters() const { return counters_; }
  size_t queued_bytes() const { return control_bytes_; }

  enum StatusLevel { kInfo = 0, kWarning = 1, kError = 2 };

 private:
  void Subscribe(const nlohmann::json& message);
  void Unsubscribe(const nlohmann::json& message);
  void Advertise(const nlohmann::json& message);
  void Unadvertise(const nlohmann::json& message);
  void FollowParameters(const nlohmann::json& message, bool follow);
  void Complain(const std::string& message);
  void Push(Outgoing message);
  std::optional<Outgoing> NextData();
  std::optional<Outgoing> NextOn(uint32_t channel, uint32_t subscription);
  std::optional<Outgoing> NextTiles(uint32_t channel, uint32_t subscription);

  ClientHub& hub_;
  int client_id_;
  std::deque<Outgoing> control_;
  size_t control_bytes_ = 0;
  bool overflowed_ = false;
  std::map<uint32_t, uint32_t> subscription_of_channel_;  ///< channel id -> the client's subscription id
  std::map<uint32_t, uint64_t> sent_;                     ///< channel id -> feed number last sent
  uint32_t round_robin_ = 0;                              ///< the channel served last
  std::map<uint32_t, ClientTiles> tiles_;                 ///< tiles channel id -> what this client has
  std::map<uint32_t, uint64_t> last_frame_sequence_;      ///< tiles channel id -> the frame last sent
  std::map<uint32_t, uint32_t> client_channels_;          ///< the client's channel id -> service id (topic)
  bool follows_all_parameters_ = false;
  std::set<std::string> followed_parameters_;
  ClientCounters counters_;
};

}  // namespace flagsim::gateway
