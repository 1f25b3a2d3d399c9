#include "client/gateway/gateway.hpp"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <variant>

#include "client/gateway/bus_json.hpp"
#include "client/gateway/foxglove_wire.hpp"
#include "client/gateway/gateway_parameters.hpp"
#include "client/gateway/mcap_export.hpp"
#include "client/gateway/recording_service.hpp"
#include "client/stream_reader.hpp"
#include "common/design_image.hpp"
#include "common/printable_text.hpp"
#include "messages/checked_decode.hpp"
#include "messages/design_pieces.hpp"

namespace flagsim::gateway {
namespace {

using nlohmann::json;

constexpr char kStatusName[] = "STATUS";

/// What a finished recording becomes: MCAP, made here, and a video where an exporter is given.
std::vector<RecordingExports::Format> ExportFormats(const Channels& channels,
                                                    const RecordingExports::Exporter& video) {
  std::vector<RecordingExports::Format> formats = {
      {"mcap", [channels](const std::string& log, const std::string& output, const std::atomic<bool>& stop) {
         try {
           ExportMcap(log, output, channels, stop);
         } catch (const std::runtime_error& error) {
           return std::string(error.what());
         }
         return std::string(stop.load() ? "stopped" : "");
       }}};
  if (video) formats.push_back({"mp4", video});
  return formats;
}

json CommandResultJson(const CommandOutcome& outcome, const std::string& channel, int64_t sequence) {
  const bool answered = outcome.result != CommandOutcome::kNoAnswer;
  return {
      {"accepted", outcome.result == CommandOutcome::kAccepted},
      {"answered", answered},
      {"reason", answered ? outcome.reason : "no answer from flagd (an ACK) within the gateway's timeout"},
      {"step", outcome.step},
      {"other_servers", outcome.other_servers},
      {"channel", channel},
      {"sequence", sequence}};
}

std::string AdvertiseText(const json& channels) {
  return json{{"op", "advertise"}, {"channels", channels}}.dump();
}

std::string AdvertiseServicesText(const json& services) {
  return json{{"op", "advertiseServices"}, {"services", services}}.dump();
}

}  // namespace

ServerSelection ServerSelection::One(const std::string& prefix) { return {false, {prefix}}; }

ServerSelection ServerSelection::Many(std::vector<std::string> prefixes) {
  return {true, std::move(prefixes)};
}

// One server: its link now, in slot 0, offered from the start, STATUS on its own channel. Many:
// STATUS on every channel that ends so, each a server found (OnStatus).
Gateway::Gateway(Bus& bus, ServerSelection servers, GatewayOptions options)
    : bus_(bus),
      selection_(std::move(servers)),
      options_(std::move(options)),
      relay_(bus, NewGatewayClientId(), options_.command_timeout, options_.signer),
      subscriptions_(bus) {
  started_ = status_window_start_ = next_status_ = options_.clock();
  const std::string channel = selection_.many ? "[A-Za-z0-9_]+" + std::string(kStatusName)
                                              : Channels(selection_.prefixes.at(0)).status;
  subscriptions_.Subscribe(channel, [this](const std::string& name, const uint8_t* data, size_t size) {
    std::string error;
    const std::optional<status_t> status =
        wire::CheckedDecode<status_t>(data, size, kMaxStreamMessageBytes, &error);
    if (status) OnStatus(name, *status);
  });
  if (!selection_.many) Offer(*LinkFor(selection_.prefixes.at(0)));
}

void Gateway::OnStatus(const std::string& channel, const status_t& status) {
  ServerLink* link = LinkFor(channel.substr(0, channel.size() - std::strlen(kStatusName)));
  if (link == nullptr) return;
  link->OnStatus(status);
  if (offered_.count(link->slot()) == 0) Offer(*link);
}

ServerLink* Gateway::LinkFor(const std::string& prefix) {
  const auto found = slots_.find(prefix);
  if (found != slots_.end()) return links_.at(found->second).get();
  const auto& wanted = selection_.prefixes;
  if (selection_.many && !wanted.empty() && std::find(wanted.begin(), wanted.end(), prefix) == wanted.end())
    return nullptr;
  if (!Channels::CheckPrefix(prefix).empty()) return nullptr;
  if (links_.size() >= kMaxServers) {
    ++counters_.servers_ignored;
    return nullptr;
  }
  const uint32_t slot = selection_.many ? uint32_t(links_.size()) + 1 : 0;
  const std::string path = selection_.many ? "/" + prefix : "";
  const std::string stem = selection_.many ? "flagsim-" + prefix : "flagsim";
  ServerLink::Hooks hooks;
  hooks.wake = [this] { WakeAll(); };
  hooks.ack = [this](const ack_t& ack) { relay_.OnAck(ack); };
  hooks.parameters_changed = [this, path](const json& changed) {
    const json renamed = RenamedValues(path, changed);
    for (auto& [id, client] : clients_) client->protocol().OnParametersChanged(renamed);
  };
  const auto make_recorder = [this, stem](const Channels& channels) {
    return std::make_unique<SessionRecorder>(bus_, channels, options_.record_directory,
                                             ExportFormats(channels, options_.video_exporter), stem);
  };
  links_[slot] = std::make_unique<ServerLink>(bus_, prefix, slot, path, relay_, make_recorder, options_.clock,
                                              std::move(hooks));
  slots_[prefix] = slot;
  offers_[slot] = {ServerChannelsJson(slot, path), ServerServicesJson(slot, path)};
  return links_[slot].get();
}

ServerLink* Gateway::LiveLink(uint32_t slot) const {
  if (offered_.count(slot) == 0) return nullptr;
  return links_.at(slot).get();
}

const ServerLink* Gateway::server(uint32_t slot) const {
  const auto found = links_.find(slot);
  return found == links_.end() ? nullptr : found->second.get();
}

void Gateway::Offer(ServerLink& link) {
  offered_.insert(link.slot());
  const auto& [channels, services] = offers_.at(link.slot());
  const std::vector<std::string> advertisements = {AdvertiseText(channels), AdvertiseServicesText(services)};
  for (auto& [id, client] : clients_) client->protocol().Announce(advertisements);
  PublishServers();
}

void Gateway::Withdraw(ServerLink& link) {
  offered_.erase(link.slot());
  const std::vector<uint32_t> channels = ServerChannelIds(link.slot());
  const std::vector<uint32_t> services = ServerServiceIds(link.slot());
  for (auto& [id, client] : clients_) client->protocol().Withdraw(channels, services);
  PublishServers();
}

std::vector<std::string> Gateway::Advertisements() const {
  json channels = json::array(), services = json::array();
  for (const uint32_t slot : offered_) {
    const auto& [its_channels, its_services] = offers_.at(slot);
    channels.insert(channels.end(), its_channels.begin(), its_channels.end());
    services.insert(services.end(), its_services.begin(), its_services.end());
  }
  const json own = GatewayChannelsJson();
  channels.insert(channels.end(), own.begin(), own.end());
  return {AdvertiseText(channels), AdvertiseServicesText(services)};
}

ClientHub::ChannelKind Gateway::KindOf(uint32_t id) const {
  if (IsGatewayChannel(id)) return ChannelKind::kFeed;
  const uint32_t base = BaseOf(id);
  if (LiveLink(SlotOf(id)) == nullptr || base < 1 || base > kServerChannelCount) return ChannelKind::kNone;
  if (base == kTilesChannel) return ChannelKind::kTiles;
  return base == kAcksChannel ? ChannelKind::kAcks : ChannelKind::kFeed;
}

ChannelFeed* Gateway::Feed(uint32_t id) {
  if (id == kGatewayStatusChannel) return &status_feed_;
  if (id == kServersChannel) return &servers_feed_;
  const ChannelKind kind = KindOf(id);
  if (kind != ChannelKind::kFeed && kind != ChannelKind::kAcks) return nullptr;
  return &LiveLink(SlotOf(id))->feed(BaseOf(id));
}

std::shared_ptr<const MirroredFrame> Gateway::Frame(uint32_t id) const {
  if (KindOf(id) != ChannelKind::kTiles) return nullptr;
  return LiveLink(SlotOf(id))->frame();
}

std::optional<uint32_t> Gateway::ServiceForTopic(std::string_view topic) const {
  for (const uint32_t slot : offered_) {
    const std::string& path = links_.at(slot)->path();
    if (topic.substr(0, path.size()) != path) continue;
    for (const ServiceInfo& service : AdvertisedServices()) {
      if (service.id != kRecordService && topic.substr(path.size()) == service.name)
        return IdIn(slot, service.id);
    }
  }
  return std::nullopt;
}

void Gateway::SubscribersChanged(uint32_t id, int delta) {
  const auto found = links_.find(SlotOf(id));
  if (!IsGatewayChannel(id) && found != links_.end()) found->second->SubscribersChanged(BaseOf(id), delta);
}

// A recording that stopped on its own (a full disk): said on stderr and to every client, beside
// the record service's answers, which carry it too.
void Gateway::RecordingEnded(const ServerLink& link, const std::string& why) {
  const std::string service = link.path() + "/flag/record";
  const std::string what = link.path().empty() ? "recording" : "recording of " + link.channels().prefix;
  std::fprintf(stderr, "flagctl serve: %s stopped: %s\n", what.c_str(), why.c_str());
  for (auto& [id, client] : clients_)
    client->protocol().SendStatus(ClientProtocol::kError, service + ": " + why);
  WakeAll();
}

void Gateway::WakeAll() {
  for (auto& [id, client] : clients_) client->Wake();
}

int Gateway::Attach(GatewayClient* client) {
  const int id = next_client_++;
  clients_[id] = client;
  return id;
}

void Gateway::Detach(int client) {
  uploads_.Drop(client);
  clients_.erase(client);
  counters_at_window_.erase(client);
}

ClientProtocol* Gateway::Client(int id) {
  const auto found = clients_.find(id);
  return found == clients_.end() ? nullptr : &found->second->protocol();
}

bool Gateway::Relay(int client, const ServerLink& link, const std::string& channel, const Command& command,
                    Reply reply, Fail fail) {
  int& in_flight = commands_in_flight_[client];
  if (in_flight >= kMaxCommandsInFlight) {
    fail("already " + std::to_string(kMaxCommandsInFlight) +
         " commands waiting for the server's answer; send more once they are answered");
    return false;
  }
  ++in_flight;
  const std::string name = link.channels().Unprefixed(channel);
  const auto done = [this, client, name, reply](const CommandOutcome& outcome, int64_t sequence) {
    if (--commands_in_flight_[client] == 0) commands_in_flight_.erase(client);
    ClientProtocol* protocol = Client(client);
    if (protocol == nullptr) return;  // the client left meanwhile
    reply(*protocol, CommandResultJson(outcome, name, sequence));
    clients_[client]->Wake();
  };
  std::visit([&](const auto& typed) { relay_.Send(channel, typed, options_.clock(), done); }, command);
  return true;
}

// request JSON => the service's command (the table) => relay => reply(result); fail(why) if none
void Gateway::ServiceRequest(int client, ServerLink& link, uint32_t base, const json& request, Reply reply,
                             Fail fail) {
  if (base == kDesignService) return DesignRequest(client, link, request, std::move(reply), std::move(fail));
  const CommandService* service = FindCommandService(base);
  if (service == nullptr) return fail("service " + std::to_string(base) + " is not one of this gateway's");
  Command command;
  const std::string problem = service->parse(request, &command);
  if (!problem.empty()) return fail(problem);
  const bool sent = Relay(client, link, link.channels().*service->channel, command, std::move(reply), fail);
  if (sent && base == kRefreshService) Client(client)->ResetTiles(IdIn(link.slot(), kTilesChannel));
}

// {"name"} => PARAM design=NAME; a part of an image => held, or whole => its DESIGN pieces in turn
void Gateway::DesignRequest(int client, ServerLink& link, const json& request, Reply reply, Fail fail) {
  DesignUploads::Step step = uploads_.Take(client, request);
  if (!step.problem.empty()) return fail(step.problem);
  if (!step.built_in.empty()) {
    param_command_t command{};
    command.names = {"design"};
    command.values = {step.built_in};
    command.num_assignments = 1;
    Relay(client, link, link.channels().param, command, std::move(reply), std::move(fail));
    return;
  }
  if (!step.whole) {
    CommandOutcome held;
    held.result = CommandOutcome::kAccepted;
    held.reason = "held " + std::to_string(step.held) + " of " + std::to_string(step.size) + " bytes";
    return reply(*Client(client), CommandResultJson(held, "DESIGN", 0));
  }
  const std::string digest = Sha256Hex(step.bytes.data(), step.bytes.size());
  RelayPieces(client, link,
              std::make_shared<const std::vector<design_piece_t>>(
                  SplitDesignFile(step.name, digest, step.bytes, relay_.client_id(), 0)),
              0, std::move(reply));
}

// One piece after another, each on its ACK; the answer to the last (or to one refused) is the
// reply. A link lives as long as the gateway, so the chain may hold it.
void Gateway::RelayPieces(int client, ServerLink& link,
                          std::shared_ptr<const std::vector<design_piece_t>> pieces, size_t index,
                          Reply reply) {
  const auto next = [this, client, &link, pieces, index, reply](ClientProtocol& protocol,
                                                                const json& result) {
    if (!result.value("accepted", false) || index + 1 == pieces->size()) return reply(protocol, result);
    RelayPieces(client, link, pieces, index + 1, reply);
  };
  const auto refused = [this, client, reply](const std::string& why) {
    if (ClientProtocol* protocol = Client(client)) reply(*protocol, {{"accepted", false}, {"reason", why}});
  };
  Relay(client, link, link.channels().design, (*pieces)[index], next, refused);
}

void Gateway::CallService(int client, uint32_t service, uint32_t call, std::string_view encoding,
                          std::string_view payload) {
  ClientProtocol* protocol = Client(client);
  const auto fail = [this, client, service, call](const std::string& message) {
    if (ClientProtocol* p = Client(client)) {
      p->SendJson(
          {{"op", "serviceCallFailure"}, {"serviceId", service}, {"callId", call}, {"message", message}});
    }
  };
  ServerLink* link = LiveLink(SlotOf(service));
  const ServiceInfo* info = FindService(BaseOf(service));
  if (protocol == nullptr) return;
  if (link == nullptr || info == nullptr)
    return fail("service " + std::to_string(service) + " is not advertised");
  if (encoding != "json")
    return fail("encoding '" + std::string(encoding) + "' is not supported; allowed json");
  const json request = json::parse(payload, nullptr, false);
  const std::string name = link->path() + std::string(info->name);
  if (request.is_discarded()) return fail(name + ": the request is not JSON");
  const auto respond = [service, call](ClientProtocol& p, const json& result) {
    p.SendBinary(ServiceCallResponse(service, call, "json", JsonText(result)));
  };
  if (info->id != kRecordService) return ServiceRequest(client, *link, info->id, request, respond, fail);
  const double now = options_.clock();
  std::string problem;
  const std::optional<json> answer = AnswerRecordRequest(link->recorder(), request, now, &problem);
  if (!answer) return fail(problem);
  // A log starts with a whole frame and a checkpoint (asked again at Tick if none comes).
  if (link->recorder().KeyframeRequestDue(now)) link->RequestKeyframe(true);
  respond(*protocol, *answer);
}

void Gateway::PublishCommand(int client, uint32_t service, std::string_view payload) {
  ServerLink* link = LiveLink(SlotOf(service));
  const ServiceInfo* info = FindService(BaseOf(service));
  const std::string topic = link && info ? link->path() + std::string(info->name) : "?";
  const auto warn = [this, client, topic](const std::string& message) {
    if (ClientProtocol* p = Client(client)) p->SendStatus(ClientProtocol::kWarning, topic + ": " + message);
  };
  if (link == nullptr || info == nullptr) return warn("the server is no longer offered");
  const json request = json::parse(payload, nullptr, false);
  if (request.is_discarded()) return warn("the message is not JSON");
  // The ACK goes to the acks channel for everyone; the publisher also hears of a rejection.
  const auto reply = [topic](ClientProtocol& p, const json& result) {
    if (!result.value("accepted", false)) {
      p.SendStatus(ClientProtocol::kWarning, topic + ": " + result.value("reason", std::string()));
    }
  };
  ServiceRequest(client, *link, info->id, request, reply, warn);
}

void Gateway::GetParameters(int client, const json& names, const std::string& id) {
  ClientProtocol* protocol = Client(client);
  if (protocol == nullptr) return;
  json values = json::array();
  for (const uint32_t slot : offered_) {
    const ServerLink& link = *links_.at(slot);
    if (!link.params()) continue;
    const json its = ParameterValuesIn(link.path(), *link.params(), names);
    values.insert(values.end(), its.begin(), its.end());
  }
  json message = {{"op", "parameterValues"}, {"parameters", values}};
  if (!id.empty()) message["id"] = id;
  protocol->SendJson(message);
}

// parameters [{name, value}] => one PARAM command to the server they belong to => after its
// ACK: a status if it was rejected, then parameterValues with the values in force (from the
// newest PARAMS, which the server publishes before it answers).
void Gateway::SetParameters(int client, const json& parameters, const std::string& id) {
  std::string problem;
  ServerLink* link = ParametersServer(parameters, &problem);
  param_command_t command{};
  json names = json::array();
  if (link) problem = ParamCommandOf(parameters, link->path(), &command, &names);
  const std::string status_id = "setParameters:" + id;
  const auto answer = [this, client, names, id, status_id](ClientProtocol& p, const json& result) {
    if (!result.value("accepted", false))
      p.SendStatus(ClientProtocol::kError, result.value("reason", std::string()), status_id);
    GetParameters(client, names, id);
  };
  const auto refuse = [this, client, answer](const std::string& why) {
    if (ClientProtocol* p = Client(client)) answer(*p, {{"accepted", false}, {"reason", why}});
  };
  if (!problem.empty()) return refuse(problem);
  Relay(client, *link, link->channels().param, command, answer, refuse);
}

// The single server; of several, the one whose path the first name starts with.
ServerLink* Gateway::ParametersServer(const json& parameters, std::string* problem) const {
  if (!selection_.many) return LiveLink(0);
  const json first = parameters.empty() ? json() : parameters[0];
  const auto name = first.is_object() ? first.find("name") : first.end();
  if (name == first.end() || !name->is_string()) {
    *problem = parameters.empty() ? "setParameters: no parameters given"
                                  : "setParameters: each parameter needs a name";
    return nullptr;
  }
  for (const uint32_t slot : offered_) {
    if (ParameterNameOf(links_.at(slot)->path(), name->get<std::string>())) return links_.at(slot).get();
  }
  *problem = "setParameters: '" + PrintableText(name->get<std::string>()) +
             "' is no parameter of a server this gateway offers now (/PREFIX/NAME)";
  return nullptr;
}

void Gateway::Tick() {
  const double now = options_.clock();
  relay_.Tick(now);
  for (auto& [slot, link] : links_) {
    if (link->recorder().StopIfDone(now)) RecordingEnded(*link, link->recorder().last_error());
    if (link->recorder().KeyframeRequestDue(now)) link->RequestKeyframe(true);
    if (selection_.many && offered_.count(slot) > 0 && now - link->last_heard() > kSilence) Withdraw(*link);
  }
  if (now >= next_status_) {
    PublishGatewayStatus(now);
    next_status_ = std::max(next_status_ + 1.0, now);
  }
}

double Gateway::NextDue() const { return std::min(relay_.NextDue(), next_status_); }

std::optional<std::string> Gateway::RecordingFile(std::string_view name) const {
  for (const auto& [slot, link] : links_) {
    if (auto file = link->recorder().FinishedFile(name)) return file;
  }
  return std::nullopt;
}

}  // namespace flagsim::gateway
