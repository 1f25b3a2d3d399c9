#include "client/gateway/gateway.hpp"

#include <cstdio>
#include <stdexcept>

#include "client/gateway/bus_json.hpp"
#include "client/gateway/command_requests.hpp"
#include "client/gateway/compressed_image.hpp"
#include "client/gateway/foxglove_wire.hpp"
#include "client/gateway/mcap_export.hpp"
#include "client/gateway/process_usage.hpp"
#include "client/gateway/scene_update.hpp"
#include "client/stream_reader.hpp"
#include "common/design_image.hpp"
#include "flagsim/refresh_request_t.hpp"
#include "messages/design_pieces.hpp"

namespace flagsim::gateway {
namespace {

using nlohmann::json;

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

/// {name: value} of the parameters whose values differ between `before` and `after`.
json ChangedValues(const std::optional<params_t>& before, const params_t& after) {
  std::map<std::string, json> old;
  if (before) {
    for (const parameter_t& p : before->parameters) old[p.name] = ParameterValue(p);
  }
  json changed = json::array();
  for (const parameter_t& p : after.parameters) {
    const json value = ParameterValue(p);
    const auto found = old.find(p.name);
    if (found == old.end() || found->second != value) changed.push_back({{"name", p.name}, {"value", value}});
  }
  return changed;
}

}  // namespace

Gateway::Gateway(Bus& bus, const Channels& channels, GatewayOptions options)
    : bus_(bus),
      channels_(channels),
      options_(std::move(options)),
      relay_(bus, NewGatewayClientId(), options_.command_timeout, options_.signer),
      recorder_(bus, channels, options_.record_directory, ExportFormats(channels, options_.video_exporter)) {
  feeds_[kAcksChannel] = ChannelFeed(kAcksKept);
  started_ = status_window_start_ = next_status_ = options_.clock();
  SubscribeBus();
  RequestKeyframe();  // the mirror fills within a frame, not at the next periodic keyframe
}

// Every subscription decodes with its lengths checked; garbage is dropped and counted, never
// trusted (a count that grows says, for one, that flagd was built from other message types).
void Gateway::SubscribeBus() {
  int64_t* dropped = &counters_.bus_undecodable;
  SubscribeDecoded<tile_t>(
      bus_, channels_.tile, [this](const tile_t& tile) { mirror_.AddTile(tile); }, dropped, 10000);
  SubscribeDecoded<frame_t>(
      bus_, channels_.frame, [this](const frame_t& frame) { OnFrame(frame); }, dropped, 1000);
  SubscribeDecoded<state_t>(
      bus_, channels_.state,
      [this](const state_t& message) {
        NoteServer(message.server_id);
        const auto state = std::make_shared<const state_t>(message);
        feeds_[kStateChannel].PublishLazily(Nanoseconds(state->utime),
                                            [state] { return JsonText(StateSummaryJson(*state)); });
        feeds_[kSceneChannel].PublishLazily(Nanoseconds(state->utime),
                                            [state] { return SceneUpdateJson(*state); });
        WakeAll();
      },
      dropped, 200);
  SubscribeDecoded<status_t>(
      bus_, channels_.status,
      [this](const status_t& status) {
        NoteServer(status.server_id);
        Publish(kStatusChannel, status.utime, JsonText(StatusJson(status)));
      },
      dropped);
  SubscribeDecoded<timeline_t>(
      bus_, channels_.timeline,
      [this](const timeline_t& timeline) {
        Publish(kTimelineChannel, timeline.utime, JsonText(TimelineJson(timeline)));
      },
      dropped);
  SubscribeDecoded<params_t>(
      bus_, channels_.params, [this](const params_t& params) { OnParams(params); }, dropped);
  SubscribeDecoded<ack_t>(
      bus_, channels_.ack, [this](const ack_t& ack) { OnAck(ack); }, dropped, 1000);
}

void Gateway::Publish(uint32_t channel, int64_t utime, std::string payload) {
  feeds_[channel].Publish(Nanoseconds(utime), std::move(payload));
  WakeAll();
}

// manifest => mirror (hash-checked) => camera and, if anyone watches it, the JPEG feed
void Gateway::OnFrame(const frame_t& manifest) {
  const FrameMirror::Result result = mirror_.AddManifest(manifest);
  if (result == FrameMirror::Result::kIncomplete) {
    ++counters_.incomplete_frames;
    if (++incomplete_in_a_row_ >= kIncompleteBeforeRefresh) RequestKeyframe();
    return;
  }
  const auto frame = mirror_.latest();
  if (result != FrameMirror::Result::kComplete || !frame || frame->frame_id != manifest.frame_id) return;
  incomplete_in_a_row_ = 0;
  ++counters_.frames_mirrored;
  const json camera = CameraJson(manifest);
  if (CameraMoved(camera, &last_camera_))
    feeds_[kCameraChannel].Publish(Nanoseconds(manifest.utime), JsonText(camera));
  if (frame->image) {
    feeds_[kImageChannel].PublishLazily(Nanoseconds(frame->utime), [frame] {
      return CompressedImageJson(EncodeJpeg(frame->image->data(), frame->width, frame->height), frame->utime);
    });
  }
  WakeAll();
}

// PARAMS => the table's channel, and parameterValues of what changed to the clients following it
void Gateway::OnParams(const params_t& params) {
  const json changed = ChangedValues(params_, params);
  params_ = params;
  feeds_[kParamsChannel].Publish(Nanoseconds(params.utime), JsonText(ParamsJson(params)));
  if (!changed.empty()) {
    for (auto& [id, client] : clients_) client->protocol().OnParametersChanged(changed);
  }
  WakeAll();
}

void Gateway::NoteServer(int64_t server_id) {
  if (server_id == 0 || server_id == server_id_) return;  // 0: a render's log, no server
  const bool restarted = server_id_ != 0;
  server_id_ = server_id;
  if (!restarted) return;
  ++counters_.server_restarts;
  mirror_.ServerRestarted();
  incomplete_in_a_row_ = 0;
  last_camera_ = nullptr;
  RequestKeyframe(true);
}

void Gateway::OnAck(const ack_t& ack) {
  feeds_[kAcksChannel].Publish(Nanoseconds(ack.utime), JsonText(AckJson(ack)));
  relay_.OnAck(ack);
  WakeAll();
}

// A recording that stopped on its own (a full disk): said on stderr and to every client, beside
// the record service's answers, which carry it too.
void Gateway::RecordingEnded(const std::string& why) {
  std::fprintf(stderr, "flagctl serve: recording stopped: %s\n", why.c_str());
  for (auto& [id, client] : clients_)
    client->protocol().SendStatus(ClientProtocol::kError, "/flag/record: " + why);
  WakeAll();
}

void Gateway::WakeAll() {
  for (auto& [id, client] : clients_) client->Wake();
}

void Gateway::RequestKeyframe(bool always) {
  const double now = options_.clock();
  if (!always && now - last_refresh_ < kRefreshInterval) return;
  last_refresh_ = now;
  relay_.Send(channels_.refresh, refresh_request_t{}, now, [](const CommandOutcome&, int64_t) {});
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

void Gateway::SubscribersChanged(uint32_t channel, int delta) {
  if (channel > kChannelCount) return;
  subscribers_[channel] += delta;
  if (channel == kImageChannel) mirror_.KeepImages(subscribers_[channel] > 0);
}

template <class Command>
void Gateway::Relay(int client, const std::string& channel, const Command& command,
                    std::function<void(ClientProtocol&, const json&)> reply) {
  const std::string name = channels_.Unprefixed(channel);
  ++commands_in_flight_[client];
  relay_.Send(channel, command, options_.clock(),
              [this, client, name, reply](const CommandOutcome& outcome, int64_t sequence) {
                if (--commands_in_flight_[client] == 0) commands_in_flight_.erase(client);
                ClientProtocol* protocol = Client(client);
                if (protocol == nullptr) return;  // the client left meanwhile
                reply(*protocol, CommandResultJson(outcome, name, sequence));
                clients_[client]->Wake();
              });
}

// request JSON => the service's command => relay => reply(result); fail(why) if it is none
void Gateway::ServiceRequest(int client, uint32_t service, const json& request,
                             std::function<void(ClientProtocol&, const json&)> reply,
                             std::function<void(const std::string&)> fail) {
  if (commands_in_flight_.count(client) > 0 && commands_in_flight_[client] >= kMaxCommandsInFlight) {
    return fail("already " + std::to_string(kMaxCommandsInFlight) +
                " commands waiting for the server's answer; send more once they are answered");
  }
  std::string problem;
  switch (service) {
    case kWindService: {
      wind_command_t command{};
      problem = WindCommandOf(request, &command);
      if (problem.empty()) Relay(client, channels_.wind, command, reply);
      break;
    }
    case kSetService: {
      param_command_t command{};
      problem = SetCommandOf(request, &command);
      if (problem.empty()) Relay(client, channels_.param, command, reply);
      break;
    }
    case kCameraService: {
      camera_command_t command{};
      problem = CameraCommandOf(request, &command);
      if (problem.empty()) Relay(client, channels_.camera, command, reply);
      break;
    }
    case kKeyframeService: {
      keyframe_command_t command{};
      problem = KeyframeCommandOf(request, &command);
      if (problem.empty()) Relay(client, channels_.keyframe, command, reply);
      break;
    }
    case kTimeService: {
      time_command_t command{};
      problem = TimeCommandOf(request, &command);
      if (problem.empty()) Relay(client, channels_.time, command, reply);
      break;
    }
    case kDesignService:
      return DesignRequest(client, request, reply, fail);
    case kRefreshService:
      Client(client)->ResetTiles();
      Relay(client, channels_.refresh, refresh_request_t{}, reply);
      break;
    default:
      problem = "service " + std::to_string(service) + " is not one of this gateway's";
  }
  if (!problem.empty()) fail(problem);
}

// {"name"} => PARAM design=NAME; a part of an image => held, or whole => its DESIGN pieces in turn
void Gateway::DesignRequest(int client, const json& request,
                            std::function<void(ClientProtocol&, const json&)> reply,
                            std::function<void(const std::string&)> fail) {
  DesignUploads::Step step = uploads_.Take(client, request);
  if (!step.problem.empty()) return fail(step.problem);
  if (!step.built_in.empty()) {
    param_command_t command{};
    command.names = {"design"};
    command.values = {step.built_in};
    command.num_assignments = 1;
    return Relay(client, channels_.param, command, reply);
  }
  if (!step.whole) {
    CommandOutcome held;
    held.result = CommandOutcome::kAccepted;
    held.reason = "held " + std::to_string(step.held) + " of " + std::to_string(step.size) + " bytes";
    return reply(*Client(client), CommandResultJson(held, "DESIGN", 0));
  }
  const std::string digest = Sha256Hex(step.bytes.data(), step.bytes.size());
  RelayPieces(client,
              std::make_shared<const std::vector<design_piece_t>>(
                  SplitDesignFile(step.name, digest, step.bytes, relay_.client_id(), 0)),
              0, std::move(reply));
}

// One piece after another, each on its ACK; the answer to the last (or to one refused) is the reply.
void Gateway::RelayPieces(int client, std::shared_ptr<const std::vector<design_piece_t>> pieces, size_t index,
                          std::function<void(ClientProtocol&, const json&)> reply) {
  Relay(client, channels_.design, (*pieces)[index],
        [this, client, pieces, index, reply](ClientProtocol& protocol, const json& result) {
          if (!result.value("accepted", false) || index + 1 == pieces->size()) return reply(protocol, result);
          RelayPieces(client, pieces, index + 1, reply);
        });
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
  const ServiceInfo* info = FindService(service);
  if (protocol == nullptr) return;
  if (info == nullptr) return fail("service " + std::to_string(service) + " is not advertised");
  if (encoding != "json")
    return fail("encoding '" + std::string(encoding) + "' is not supported; allowed json");
  const json request = json::parse(payload, nullptr, false);
  if (request.is_discarded()) return fail(std::string(info->name) + ": the request is not JSON");
  const auto respond = [service, call](ClientProtocol& p, const json& result) {
    p.SendBinary(ServiceCallResponse(service, call, "json", JsonText(result)));
  };
  if (service == kRecordService) {
    const std::string action = request.is_object() ? request.value("action", "") : "";
    const double now = options_.clock();
    if (action == "start") {
      const json state = recorder_.Start(now);
      // The log starts with a whole frame and a checkpoint (asked again at Tick if none comes).
      if (recorder_.KeyframeRequestDue(now)) RequestKeyframe(true);
      return respond(*protocol, state);
    }
    if (action == "stop") return respond(*protocol, recorder_.Stop(now));
    if (action == "status") return respond(*protocol, recorder_.Status(now));
    return fail("/flag/record: action must be start, stop or status");
  }
  ServiceRequest(client, service, request, respond, fail);
}

void Gateway::PublishCommand(int client, uint32_t service, std::string_view payload) {
  const ServiceInfo* info = FindService(service);
  const std::string topic(info ? info->name : "?");
  const auto warn = [this, client, topic](const std::string& message) {
    if (ClientProtocol* p = Client(client)) p->SendStatus(ClientProtocol::kWarning, topic + ": " + message);
  };
  const json request = json::parse(payload, nullptr, false);
  if (request.is_discarded()) return warn("the message is not JSON");
  // The ACK goes to /flag/acks for everyone; the publisher also hears of a rejection.
  const auto reply = [topic](ClientProtocol& p, const json& result) {
    if (!result.value("accepted", false)) {
      p.SendStatus(ClientProtocol::kWarning, topic + ": " + result.value("reason", std::string()));
    }
  };
  ServiceRequest(client, service, request, reply, warn);
}

void Gateway::GetParameters(int client, const json& names, const std::string& id) {
  ClientProtocol* protocol = Client(client);
  if (protocol == nullptr) return;
  json values = json::array();
  if (params_) {
    for (const json& value : ParameterValues(*params_)) {
      const bool wanted =
          names.empty() || std::find(names.begin(), names.end(), value["name"]) != names.end();
      if (wanted) values.push_back(value);
    }
  }
  json message = {{"op", "parameterValues"}, {"parameters", values}};
  if (!id.empty()) message["id"] = id;
  protocol->SendJson(message);
}

// parameters [{name, value}] => one PARAM command => after its ACK: a status if it was
// rejected, then parameterValues with the values in force (from the newest PARAMS, which the
// server publishes before it answers).
void Gateway::SetParameters(int client, const json& parameters, const std::string& id) {
  param_command_t command{};
  json names = json::array();
  std::string problem;
  for (const json& parameter : parameters) {
    const auto name = parameter.find("name");
    const auto value = parameter.find("value");
    if (!parameter.is_object() || name == parameter.end() || !name->is_string()) {
      problem = "setParameters: each parameter needs a name";
      break;
    }
    if (value == parameter.end()) {
      problem = name->get<std::string>() + ": parameters cannot be unset; give a value";
      break;
    }
    const std::string text = ParameterText(name->get<std::string>(), *value, &problem);
    if (!problem.empty()) break;
    command.names.push_back(name->get<std::string>());
    command.values.push_back(text);
    names.push_back(*name);
  }
  command.num_assignments = static_cast<int32_t>(command.names.size());
  const std::string status_id = "setParameters:" + id;
  const auto answer = [this, client, names, id, status_id](ClientProtocol& p, const json& result) {
    if (!result.value("accepted", false)) {
      p.SendStatus(ClientProtocol::kError, result.value("reason", std::string()), status_id);
    }
    GetParameters(client, names, id);
  };
  if (problem.empty() && command.num_assignments == 0) problem = "setParameters: no parameters given";
  if (problem.empty() && commands_in_flight_.count(client) > 0 &&
      commands_in_flight_[client] >= kMaxCommandsInFlight) {
    problem =
        "setParameters: already " + std::to_string(kMaxCommandsInFlight) + " commands waiting for an answer";
  }
  if (!problem.empty()) {
    if (ClientProtocol* p = Client(client)) answer(*p, {{"accepted", false}, {"reason", problem}});
    return;
  }
  Relay(client, channels_.param, command, answer);
}

void Gateway::Tick() {
  const double now = options_.clock();
  relay_.Tick(now);
  if (recorder_.StopIfDone(now)) RecordingEnded(recorder_.last_error());
  if (recorder_.KeyframeRequestDue(now)) RequestKeyframe(true);
  if (now >= next_status_) {
    PublishGatewayStatus(now);
    next_status_ = std::max(next_status_ + 1.0, now);
  }
}

double Gateway::NextDue() const { return std::min(relay_.NextDue(), next_status_); }

void Gateway::PublishGatewayStatus(double now) {
  const double window = std::max(now - status_window_start_, 1e-3);
  json per_client = json::array();
  double bytes_per_second = 0;
  for (auto& [id, client] : clients_) {
    const ClientCounters& counters = client->protocol().counters();
    const ClientCounters before = counters_at_window_[id];
    const double rate = double(counters.bytes_sent - before.bytes_sent) / window;
    bytes_per_second += rate;
    per_client.push_back({{"id", id},
                          {"address", client->address()},
                          {"bytes_per_second", rate},
                          {"frames_per_second", double(counters.frames_sent - before.frames_sent) / window},
                          {"frames_skipped", counters.frames_skipped},
                          {"queued_bytes", client->protocol().queued_bytes()}});
    counters_at_window_[id] = counters;
  }
  const ProcessUsage usage = ReadProcessUsage();
  const json status = {{"uptime", now - started_},
                       {"clients", clients_.size()},
                       {"clients_dropped", counters_.clients_dropped},
                       {"unauthorized", counters_.unauthorized},
                       {"forbidden", counters_.forbidden},
                       {"protocol_errors", counters_.protocol_errors},
                       {"frames_per_second", double(counters_.frames_mirrored - frames_at_window_) / window},
                       {"incomplete_frames", counters_.incomplete_frames},
                       {"server_restarts", counters_.server_restarts},
                       {"bus_undecodable", counters_.bus_undecodable},
                       {"cpu_seconds", usage.cpu_seconds},
                       {"resident_bytes", usage.resident_bytes},
                       {"bytes_per_second", bytes_per_second},
                       {"per_client", per_client}};
  frames_at_window_ = counters_.frames_mirrored;
  status_window_start_ = now;
  Publish(kGatewayStatusChannel, UnixMicros(), JsonText(status));
}

}  // namespace flagsim::gateway
