#include "client/gateway/server_link.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <map>

#include "client/gateway/bus_json.hpp"
#include "client/gateway/compressed_image.hpp"
#include "client/gateway/scene_update.hpp"
#include "client/stream_reader.hpp"
#include "flagsim/refresh_request_t.hpp"
#include "flagsim/state_t.hpp"
#include "flagsim/tile_t.hpp"
#include "flagsim/timeline_t.hpp"
#include "messages/utime.hpp"

namespace flagsim::gateway {
namespace {

using nlohmann::json;

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

/// "32 x 24 nodes, 1.5 x 1 m, nordic_cross" from the table's cols, rows, width, height, design.
std::string SceneText(const params_t& params) {
  std::map<std::string, std::string> value;
  for (const parameter_t& p : params.parameters) {
    const json v = ParameterValue(p);
    char number[32];
    if (v.is_number()) std::snprintf(number, sizeof(number), "%g", v.get<double>());
    value[p.name] = v.is_string() ? v.get<std::string>() : v.is_number() ? std::string(number) : v.dump();
  }
  return value["cols"] + " x " + value["rows"] + " nodes, " + value["width"] + " x " + value["height"] +
         " m, " + value["design"];
}

}  // namespace

ServerLink::ServerLink(Bus& bus, const std::string& prefix, uint32_t slot, std::string path,
                       CommandRelay& relay, const RecorderMaker& make_recorder, std::function<double()> clock,
                       Hooks hooks)
    : channels_(prefix),
      slot_(slot),
      path_(std::move(path)),
      relay_(relay),
      recorder_(make_recorder(channels_)),
      clock_(std::move(clock)),
      hooks_(std::move(hooks)),
      last_heard_(-std::numeric_limits<double>::infinity()),
      subscriptions_(bus) {
  feeds_[kAcksChannel] = ChannelFeed(kAcksKept);
  Subscribe();
  RequestKeyframe();  // the mirror fills within a frame, not at the next periodic keyframe
}

// Every subscription decodes with its lengths checked; garbage is dropped and counted, never
// trusted (a count that grows says, for one, that flagd was built from other message types).
void ServerLink::Subscribe() {
  On<tile_t>(
      channels_.tile, [this](const tile_t& tile) { mirror_.AddTile(tile); }, 10000);
  On<frame_t>(
      channels_.frame, [this](const frame_t& frame) { OnFrame(frame); }, 1000);
  On<state_t>(
      channels_.state,
      [this](const state_t& message) {
        NoteServer(message.server_id);
        const auto state = std::make_shared<const state_t>(message);
        feeds_[kStateChannel].PublishLazily(Nanoseconds(state->utime),
                                            [state] { return JsonText(StateSummaryJson(*state)); });
        feeds_[kSceneChannel].PublishLazily(Nanoseconds(state->utime),
                                            [state] { return SceneUpdateJson(*state); });
        hooks_.wake();
      },
      200);
  On<timeline_t>(channels_.timeline, [this](const timeline_t& timeline) {
    Publish(kTimelineChannel, timeline.utime, JsonText(TimelineJson(timeline)));
  });
  On<params_t>(channels_.params, [this](const params_t& params) { OnParams(params); });
  On<ack_t>(
      channels_.ack,
      [this](const ack_t& ack) {
        feeds_[kAcksChannel].Publish(Nanoseconds(ack.utime), JsonText(AckJson(ack)));
        hooks_.ack(ack);
        hooks_.wake();
      },
      1000);
}

template <class Message>
void ServerLink::On(const std::string& channel, std::function<void(const Message&)> handler, int capacity) {
  subscriptions_.Subscribe(channel, DecodingHandler<Message>(std::move(handler), &counters_.bus_undecodable),
                           capacity);
}

void ServerLink::OnStatus(const status_t& status) {
  last_heard_ = clock_();
  NoteServer(status.server_id);
  status_ = status;
  Publish(kStatusChannel, status.utime, JsonText(StatusJson(status)));
}

void ServerLink::Publish(uint32_t base, int64_t utime, std::string payload) {
  feeds_[base].Publish(Nanoseconds(utime), std::move(payload));
  hooks_.wake();
}

// manifest => mirror (hash-checked) => camera and, if anyone watches it, the JPEG feed
void ServerLink::OnFrame(const frame_t& manifest) {
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
  hooks_.wake();
}

// PARAMS => the table's channel, and the values that changed to the hub
void ServerLink::OnParams(const params_t& params) {
  const json changed = ChangedValues(params_, params);
  params_ = params;
  feeds_[kParamsChannel].Publish(Nanoseconds(params.utime), JsonText(ParamsJson(params)));
  if (!changed.empty()) hooks_.parameters_changed(changed);
  hooks_.wake();
}

void ServerLink::NoteServer(int64_t server_id) {
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

void ServerLink::RequestKeyframe(bool always) {
  const double now = clock_();
  if (!always && now - last_refresh_ < kRefreshInterval) return;
  last_refresh_ = now;
  relay_.Send(channels_.refresh, refresh_request_t{}, now, [](const CommandOutcome&, int64_t) {});
}

void ServerLink::SubscribersChanged(uint32_t base, int delta) {
  if (base < 1 || base > kServerChannelCount) return;
  subscribers_[base] += delta;
  if (base == kImageChannel) mirror_.KeepImages(subscribers_[base] > 0);
}

json ServerLink::Summary(bool live, double frames_per_second) const {
  const auto latest = mirror_.latest();
  return {{"prefix", channels_.prefix},
          {"path", path_},
          {"live", live},
          {"scene", params_ ? SceneText(*params_) : ""},
          {"width", latest ? latest->width : 0},
          {"height", latest ? latest->height : 0},
          {"real_time_factor", status_ ? status_->real_time_factor : 0.0},
          {"frame_rate_hz", status_ ? status_->frame_rate_hz : 0.0},
          {"frames_per_second", frames_per_second},
          {"paused", status_ ? bool(status_->paused) : false},
          {"sim_time", status_ ? status_->sim_time : 0.0}};
}

}  // namespace flagsim::gateway
