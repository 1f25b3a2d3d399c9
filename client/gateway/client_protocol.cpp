#include "client/gateway/client_protocol.hpp"

#include <algorithm>

#include "client/gateway/bus_json.hpp"
#include "client/gateway/foxglove_wire.hpp"
#include "client/gateway/gateway_catalog.hpp"
#include "common/printable_text.hpp"

namespace flagsim::gateway {
namespace {

using nlohmann::json;

/// The unsigned 32-bit integer `value` holds; nullopt if it is none.
std::optional<uint32_t> Id(const json& value) {
  if (!value.is_number_integer()) return std::nullopt;
  const int64_t id = value.get<int64_t>();
  if (id < 0 || id > int64_t(UINT32_MAX)) return std::nullopt;
  return static_cast<uint32_t>(id);
}

/// The array `message[field]`, or an empty one (with *problem set) if it is missing or not one.
const json& ArrayField(const json& message, const char* field, std::string* problem) {
  static const json kEmpty = json::array();
  const auto found = message.find(field);
  if (found == message.end() || !found->is_array()) {
    *problem = std::string(message.value("op", "")) + ": '" + field + "' must be an array";
    return kEmpty;
  }
  return *found;
}

/// "" if a client may follow `name`, as one of `count` names; else why not.
std::string CheckFollowedName(const std::string& name, size_t count) {
  if (name.size() > ClientProtocol::kMaxParameterNameLength) {
    return "'" + PrintableText(name) + "' is " + std::to_string(name.size()) +
           " characters long; allowed parameter names of up to " +
           std::to_string(ClientProtocol::kMaxParameterNameLength) + " characters";
  }
  if (count > ClientProtocol::kMaxFollowedParameters) {
    return std::to_string(count) + " names would be followed; allowed at most " +
           std::to_string(ClientProtocol::kMaxFollowedParameters) +
           " per client (the parameter table has fewer; no names follows them all)";
  }
  return "";
}

}  // namespace

ClientProtocol::ClientProtocol(ClientHub& hub, int client_id) : hub_(hub), client_id_(client_id) {}

ClientProtocol::~ClientProtocol() {
  for (const auto& [channel, subscription] : subscription_of_channel_) hub_.SubscribersChanged(channel, -1);
}

void ClientProtocol::Start(const std::string& server_name, const std::string& session_id) {
  Push({false, ServerInfoMessage(server_name, session_id), nullptr});
  Announce(hub_.Advertisements());
}

void ClientProtocol::Announce(const std::vector<std::string>& advertisements) {
  for (const std::string& message : advertisements) Push({false, message, nullptr});
}

void ClientProtocol::Withdraw(const std::vector<uint32_t>& channels, const std::vector<uint32_t>& services) {
  for (const uint32_t channel : channels) {
    if (subscription_of_channel_.erase(channel) > 0) hub_.SubscribersChanged(channel, -1);
    sent_.erase(channel);
    tiles_.erase(channel);
    last_frame_sequence_.erase(channel);
  }
  for (auto it = client_channels_.begin(); it != client_channels_.end();) {
    const bool gone = std::find(services.begin(), services.end(), it->second) != services.end();
    it = gone ? client_channels_.erase(it) : std::next(it);
  }
  SendJson({{"op", "unadvertise"}, {"channelIds", channels}});
  SendJson({{"op", "unadvertiseServices"}, {"serviceIds", services}});
}

void ClientProtocol::Push(Outgoing message) {
  control_bytes_ += message.size();
  control_.push_back(std::move(message));
  if (control_bytes_ > kMaxControlBytes) overflowed_ = true;
}

void ClientProtocol::SendJson(const json& message) { Push({false, JsonText(message), nullptr}); }

void ClientProtocol::SendBinary(std::string frame) { Push({true, std::move(frame), nullptr}); }

void ClientProtocol::SendStatus(int level, const std::string& message, const std::string& id) {
  json status = {{"op", "status"}, {"level", level}, {"message", message}};
  if (!id.empty()) status["id"] = id;
  SendJson(status);
}

void ClientProtocol::Complain(const std::string& message) {
  hub_.CountProtocolError();
  SendStatus(kError, message);
}

// text => JSON op => subscriptions, client channels, parameters; anything else is answered
// with an error status and changes nothing.
void ClientProtocol::OnText(std::string_view text) {
  const json message = json::parse(text, nullptr, false);
  if (message.is_discarded() || !message.is_object() || !message.contains("op") ||
      !message["op"].is_string()) {
    return Complain("a text message must be a JSON object with a string 'op'");
  }
  const std::string op = message["op"];
  if (op == "subscribe") return Subscribe(message);
  if (op == "unsubscribe") return Unsubscribe(message);
  if (op == "advertise") return Advertise(message);
  if (op == "unadvertise") return Unadvertise(message);
  if (op == "subscribeParameterUpdates") return FollowParameters(message, true);
  if (op == "unsubscribeParameterUpdates") return FollowParameters(message, false);
  if (op == "getParameters" || op == "setParameters") {
    const std::string id =
        message.contains("id") && message["id"].is_string() ? message["id"].get<std::string>() : "";
    std::string problem;
    const json& list = ArrayField(message, op == "getParameters" ? "parameterNames" : "parameters", &problem);
    if (!problem.empty()) return Complain(problem);
    if (op == "getParameters") return hub_.GetParameters(client_id_, list, id);
    return hub_.SetParameters(client_id_, list, id);
  }
  Complain("op '" + op + "' is not supported by this gateway");
}

void ClientProtocol::OnBinary(std::string_view bytes) {
  std::string error;
  const std::optional<ClientBinary> message = ParseClientBinary(bytes, &error);
  if (!message) return Complain(error);
  if (message->opcode == kServiceCallRequest) {
    return hub_.CallService(client_id_, message->service, message->call, message->encoding, message->payload);
  }
  const auto channel = client_channels_.find(message->channel);
  if (channel == client_channels_.end()) {
    return Complain("Client Message Data on channel " + std::to_string(message->channel) +
                    ", never advertised");
  }
  hub_.PublishCommand(client_id_, channel->second, message->payload);
}

void ClientProtocol::Subscribe(const json& message) {
  std::string problem;
  for (const json& subscription : ArrayField(message, "subscriptions", &problem)) {
    const auto id = subscription.is_object() ? Id(subscription.value("id", json())) : std::nullopt;
    const auto channel =
        subscription.is_object() ? Id(subscription.value("channelId", json())) : std::nullopt;
    const ClientHub::ChannelKind kind = channel ? hub_.KindOf(*channel) : ClientHub::ChannelKind::kNone;
    if (!id || kind == ClientHub::ChannelKind::kNone) {
      Complain("subscribe: " + JsonText(subscription) +
               " needs an id and a channelId of an advertised channel");
      continue;
    }
    bool id_taken = false;
    for (const auto& [c, s] : subscription_of_channel_) id_taken |= s == *id;
    if (id_taken || subscription_of_channel_.count(*channel) > 0) {
      Complain("subscribe: subscription " + std::to_string(*id) + " or channel " + std::to_string(*channel) +
               " is in use already");
      continue;
    }
    subscription_of_channel_[*channel] = *id;
    // The newest message at once (latest wins); ACKs from now on only.
    sent_[*channel] = kind == ClientHub::ChannelKind::kAcks ? hub_.Feed(*channel)->newest() : 0;
    if (kind == ClientHub::ChannelKind::kTiles) tiles_[*channel].Reset();
    hub_.SubscribersChanged(*channel, +1);
  }
  if (!problem.empty()) Complain(problem);
}

void ClientProtocol::Unsubscribe(const json& message) {
  std::string problem;
  for (const json& value : ArrayField(message, "subscriptionIds", &problem)) {
    const auto id = Id(value);
    for (auto it = subscription_of_channel_.begin(); id && it != subscription_of_channel_.end(); ++it) {
      if (it->second != *id) continue;
      hub_.SubscribersChanged(it->first, -1);
      subscription_of_channel_.erase(it);
      break;
    }
  }
  if (!problem.empty()) Complain(problem);
}

// Client publishing: only the command services' topics, in JSON.
void ClientProtocol::Advertise(const json& message) {
  std::string problem;
  for (const json& channel : ArrayField(message, "channels", &problem)) {
    const auto id = channel.is_object() ? Id(channel.value("id", json())) : std::nullopt;
    const std::string topic = channel.is_object() ? channel.value("topic", "") : "";
    const std::string encoding = channel.is_object() ? channel.value("encoding", "") : "";
    const std::optional<uint32_t> service = hub_.ServiceForTopic(topic);
    if (!id || !service || encoding != "json") {
      Complain("advertise: '" + PrintableText(topic) +
               "' in json is not a topic to publish on; allowed a command service's name (/flag/wind, "
               "/flag/set, /flag/camera, /flag/keyframe, /flag/refresh, /flag/time, /flag/design; "
               "/PREFIX/flag/wind ... on a gateway of several servers) with encoding json");
      continue;
    }
    if (client_channels_.size() >= kMaxClientChannels && client_channels_.count(*id) == 0) {
      Complain("advertise: at most " + std::to_string(kMaxClientChannels) + " client channels");
      continue;
    }
    client_channels_[*id] = *service;
  }
  if (!problem.empty()) Complain(problem);
}

void ClientProtocol::Unadvertise(const json& message) {
  std::string problem;
  for (const json& value : ArrayField(message, "channelIds", &problem)) {
    if (const auto id = Id(value)) client_channels_.erase(*id);
  }
  if (!problem.empty()) Complain(problem);
}

// No names: all parameters (or none). Names are followed up to kMaxFollowedParameters of at most
// kMaxParameterNameLength characters, a message's names all or none of them; an unknown name is
// kept (the table may not have come yet) but never matches.
void ClientProtocol::FollowParameters(const json& message, bool follow) {
  std::string problem;
  const json& names = ArrayField(message, "parameterNames", &problem);
  if (!problem.empty()) return Complain(problem);
  if (names.empty()) {
    follows_all_parameters_ = follow;
    if (!follow) followed_parameters_.clear();
  }
  std::set<std::string> followed = followed_parameters_;
  for (const json& name : names) {
    if (!name.is_string()) continue;
    const std::string& text = name.get_ref<const std::string&>();
    if (!follow) {
      followed.erase(text);
      continue;
    }
    problem = CheckFollowedName(text, followed.size() + (followed.count(text) ? 0 : 1));
    if (!problem.empty())
      return Complain("subscribeParameterUpdates: " + problem + "; none of this message's names followed");
    followed.insert(text);
  }
  followed_parameters_ = std::move(followed);
}

void ClientProtocol::OnParametersChanged(const json& values) {
  json followed = json::array();
  for (const json& value : values) {
    if (follows_all_parameters_ || followed_parameters_.count(value["name"].get<std::string>()) > 0) {
      followed.push_back(value);
    }
  }
  if (!followed.empty()) SendJson({{"op", "parameterValues"}, {"parameters", followed}});
}

std::optional<Outgoing> ClientProtocol::Next() {
  std::optional<Outgoing> next;
  if (!control_.empty()) {
    next = std::move(control_.front());
    control_.pop_front();
    control_bytes_ -= next->size();
  } else {
    next = NextData();
  }
  if (next) counters_.bytes_sent += next->size();
  return next;
}

// Round robin over the subscribed channels, starting after the one served last.
std::optional<Outgoing> ClientProtocol::NextData() {
  if (subscription_of_channel_.empty()) return std::nullopt;
  auto start = subscription_of_channel_.upper_bound(round_robin_);
  for (size_t visited = 0; visited < subscription_of_channel_.size(); ++visited, ++start) {
    if (start == subscription_of_channel_.end()) start = subscription_of_channel_.begin();
    std::optional<Outgoing> message = NextOn(start->first, start->second);
    if (message) {
      round_robin_ = start->first;
      return message;
    }
  }
  return std::nullopt;
}

std::optional<Outgoing> ClientProtocol::NextOn(uint32_t channel, uint32_t subscription) {
  if (hub_.KindOf(channel) == ClientHub::ChannelKind::kTiles) return NextTiles(channel, subscription);
  ChannelFeed* feed = hub_.Feed(channel);
  if (feed == nullptr) return std::nullopt;
  while (const FeedMessage* message = feed->Next(sent_[channel])) {
    sent_[channel] = message->number;
    if (message->payload->empty()) continue;  // nothing to say (a state that made no scene)
    return Outgoing{true, MessageDataHead(subscription, message->timestamp_ns), message->payload};
  }
  return std::nullopt;
}

// The tiles that take this client from the frame it has to the newest one.
std::optional<Outgoing> ClientProtocol::NextTiles(uint32_t channel, uint32_t subscription) {
  const std::shared_ptr<const MirroredFrame> frame = hub_.Frame(channel);
  if (!frame) return std::nullopt;
  uint64_t& last_sequence = last_frame_sequence_[channel];
  const uint64_t previous = last_sequence;
  std::shared_ptr<const std::string> update = TileUpdateFor(*frame, &tiles_[channel]);
  if (!update) return std::nullopt;
  last_sequence = frame->sequence;
  if (previous > 0 && frame->sequence > previous + 1)
    counters_.frames_skipped += frame->sequence - previous - 1;
  ++counters_.frames_sent;
  return Outgoing{true, MessageDataHead(subscription, uint64_t(std::max<int64_t>(frame->utime, 0)) * 1000),
                  std::move(update)};
}

}  // namespace flagsim::gateway
