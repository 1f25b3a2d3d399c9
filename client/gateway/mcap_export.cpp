#include "client/gateway/mcap_export.hpp"

#include <optional>
#include <stdexcept>
#include <string_view>

#include "client/gateway/bus_json.hpp"
#include "client/gateway/compressed_image.hpp"
#include "client/gateway/frame_mirror.hpp"
#include "client/gateway/gateway_catalog.hpp"
#include "client/gateway/scene_update.hpp"
#include "client/mcap_writer.hpp"
#include "flagsim/ack_t.hpp"
#include "flagsim/frame_t.hpp"
#include "flagsim/params_t.hpp"
#include "flagsim/state_t.hpp"
#include "flagsim/status_t.hpp"
#include "flagsim/tile_t.hpp"
#include "flagsim/timeline_t.hpp"
#include "messages/checked_decode.hpp"
#include "messages/event_log_reader.hpp"

namespace flagsim::gateway {
namespace {

constexpr size_t kMaxMessageBytes = 1 << 20;

/// The live view's JSON channels in the file: each with its schema, written as the gateway
/// advertises it.
class McapChannels {
 public:
  explicit McapChannels(McapWriter& writer) : writer_(writer) {
    for (const ChannelInfo& channel : AdvertisedChannels()) {
      if (channel.encoding != "json" || IsGatewayChannel(channel.id)) continue;  // the gateway's own
      const uint16_t schema =
          writer.AddSchema(channel.schema_name, channel.schema_encoding, Schema(channel.schema_file));
      ids_[channel.id] = writer.AddChannel(schema, channel.topic, channel.encoding);
      topics_[channel.id] = std::string(channel.topic);
    }
  }

  /// One message on `channel`, recorded at `log_us` and stamped by the server at `utime` (us).
  void Write(ChannelId channel, int64_t log_us, int64_t utime, std::string_view json,
             McapExportReport* report) {
    writer_.Write(ids_.at(channel), Nanoseconds(log_us), Nanoseconds(utime), json);
    ++report->messages[topics_.at(channel)];
  }

 private:
  McapWriter& writer_;
  std::map<uint32_t, uint16_t> ids_;
  std::map<uint32_t, std::string> topics_;
};

/// One server's events, in the log's order, into the channels.
class SessionConverter {
 public:
  SessionConverter(const Channels& channels, McapChannels& out, McapExportReport* report)
      : channels_(channels), out_(out), report_(report) {
    mirror_.KeepImages(true);
  }

  void Convert(const LogEvent& event) {
    const std::string& channel = event.channel;
    if (channel == channels_.tile) {
      if (const auto tile = Decode<tile_t>(event)) mirror_.AddTile(*tile);
    } else if (channel == channels_.frame) {
      if (const auto frame = Decode<frame_t>(event)) OnFrame(event.timestamp, *frame);
    } else if (channel == channels_.state) {
      if (const auto state = Decode<state_t>(event)) {
        NoteServer(state->server_id);
        out_.Write(kStateChannel, event.timestamp, state->utime, JsonText(StateSummaryJson(*state)), report_);
        out_.Write(kSceneChannel, event.timestamp, state->utime, SceneUpdateJson(*state), report_);
      }
    } else if (channel == channels_.status) {
      if (const auto status = Decode<status_t>(event)) {
        NoteServer(status->server_id);
        out_.Write(kStatusChannel, event.timestamp, status->utime, JsonText(StatusJson(*status)), report_);
      }
    } else if (channel == channels_.params) {
      if (const auto params = Decode<params_t>(event))
        out_.Write(kParamsChannel, event.timestamp, params->utime, JsonText(ParamsJson(*params)), report_);
    } else if (channel == channels_.timeline) {
      if (const auto timeline = Decode<timeline_t>(event))
        out_.Write(kTimelineChannel, event.timestamp, timeline->utime, JsonText(TimelineJson(*timeline)),
                   report_);
    } else if (channel == channels_.ack) {
      if (const auto ack = Decode<ack_t>(event))
        out_.Write(kAcksChannel, event.timestamp, ack->utime, JsonText(AckJson(*ack)), report_);
    }
  }

 private:
  template <class Message>
  std::optional<Message> Decode(const LogEvent& event) {
    std::string error;
    std::optional<Message> message =
        wire::CheckedDecode<Message>(event.data.data(), event.data.size(), kMaxMessageBytes, &error);
    if (!message) ++report_->undecodable;
    return message;
  }

  // manifest => a whole frame: the camera when it moved, and the image as JPEG
  void OnFrame(int64_t log_us, const frame_t& manifest) {
    const FrameMirror::Result result = mirror_.AddManifest(manifest);
    if (result == FrameMirror::Result::kIncomplete) ++report_->incomplete_frames;
    const auto frame = mirror_.latest();
    if (result != FrameMirror::Result::kComplete || !frame || frame->frame_id != manifest.frame_id) return;
    const nlohmann::json camera = CameraJson(manifest);
    if (CameraMoved(camera, &last_camera_))
      out_.Write(kCameraChannel, log_us, manifest.utime, JsonText(camera), report_);
    const std::string jpeg = EncodeJpeg(frame->image->data(), frame->width, frame->height);
    out_.Write(kImageChannel, log_us, frame->utime, CompressedImageJson(jpeg, frame->utime), report_);
  }

  void NoteServer(int64_t server_id) {
    if (server_id == 0 || server_id == server_id_) return;
    if (server_id_ != 0) {
      mirror_.ServerRestarted();
      last_camera_ = nullptr;
    }
    server_id_ = server_id;
  }

  const Channels& channels_;
  McapChannels& out_;
  McapExportReport* report_;
  FrameMirror mirror_;
  nlohmann::json last_camera_;
  int64_t server_id_ = 0;
};

}  // namespace

int64_t McapExportReport::total() const {
  int64_t sum = 0;
  for (const auto& [topic, count] : messages) sum += count;
  return sum;
}

McapExportReport ExportMcap(const std::string& log_path, const std::string& mcap_path,
                            const Channels& channels, const std::atomic<bool>& stop,
                            const std::function<void(double)>& progress) {
  EventLogReader reader(log_path);
  McapWriter writer(mcap_path);
  McapChannels out(writer);
  McapExportReport report;
  SessionConverter converter(channels, out, &report);
  const auto ours = [&channels](const std::string& channel) {
    return channel.rfind(channels.prefix, 0) == 0;
  };
  LogEvent event;
  int64_t events = 0;
  while (!stop.load() && reader.Next(&event, ours)) {
    if (ours(event.channel)) converter.Convert(event);
    if (progress && ++events % 256 == 0 && reader.size() > 0)
      progress(double(reader.offset()) / double(reader.size()));
  }
  report.log_problem = reader.problem();
  const std::string closed = writer.Close();
  if (!closed.empty()) throw std::runtime_error(closed);
  return report;
}

}  // namespace flagsim::gateway
