// Writes the fuzz targets' seed corpora (tests/fuzz/corpus/<target>/): real, valid inputs, small.
//
//   a live session   flagd's loop on an in-process bus, steered and recorded as flagctl would
//                    (corpus_session.hpp): its log is the event log and replay seed, and its
//                    messages by channel are the command, stream and checkpoint seeds
//   commands         each camera and keyframe operation and parameter change flagctl can send
//   the protocol     what a Foxglove client sends the gateway: JSON ops and binary frames
//   files            the scene presets and examples, PNGs, key files, HTTP requests
//
//   build/tests/fuzz/fuzz_make_corpus SOURCE_DIR     (rewrites SOURCE_DIR/tests/fuzz/corpus)
//
// Seeds of the targets that take several messages are records (fuzz_records.hpp).
#include <png.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "client/gateway/foxglove_wire.hpp"
#include "client/gateway/gateway_catalog.hpp"
#include "common/jpeg_file.hpp"
#include "common/png_file.hpp"
#include "flagsim/camera_command_t.hpp"
#include "flagsim/keyframe_command_t.hpp"
#include "flagsim/param_command_t.hpp"
#include "flagsim/refresh_request_t.hpp"
#include "flagsim/wind_command_t.hpp"
#include "messages/channels.hpp"
#include "messages/command_key.hpp"
#include "messages/event_log_reader.hpp"
#include "messages/publisher.hpp"
#include "server/scene/scene_file.hpp"
#include "tests/fuzz/command_server.hpp"
#include "tests/fuzz/corpus_session.hpp"
#include "tests/fuzz/fuzz_records.hpp"

using namespace flagsim;
using namespace flagsim::fuzz;
namespace fs = std::filesystem;
using Bytes = std::vector<uint8_t>;
using nlohmann::json;

namespace {

constexpr double kRadiansPerDegree = M_PI / 180;

fs::path g_corpus;  ///< SOURCE_DIR/tests/fuzz/corpus

void Write(const std::string& target, const std::string& name, const Bytes& bytes) {
  const fs::path directory = g_corpus / target;
  fs::create_directories(directory);
  std::ofstream(directory / name, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

Bytes Text(const std::string& text) { return Bytes(text.begin(), text.end()); }

Bytes Concatenated(const std::vector<Bytes>& parts) {
  Bytes all;
  for (const Bytes& part : parts) all.insert(all.end(), part.begin(), part.end());
  return all;
}

Bytes ReadFile(const fs::path& path) {
  std::ifstream stream(path, std::ios::binary);
  return Bytes((std::istreambuf_iterator<char>(stream)), std::istreambuf_iterator<char>());
}

// ---- seeds -----------------------------------------------------------------------------------

/// The server's targets: each command of the session alone and all in order (the session
/// stepping after each), another server's STATUS, and commands the session did not send.
void CommandSeeds(const std::vector<LogEvent>& events, const Channels& channels) {
  const std::map<std::string, uint8_t> selector = {
      {channels.wind, 0},    {channels.param, 1},  {channels.camera, 2}, {channels.keyframe, 3},
      {channels.refresh, 4}, {channels.status, 5}, {channels.time, 6},   {channels.design, 7}};
  std::vector<Bytes> in_order, signed_in_order;
  std::map<std::string, int> count;
  for (const LogEvent& event : events) {
    const auto found = selector.find(event.channel);
    if (found == selector.end() || (event.channel == channels.status && count[event.channel] > 0)) continue;
    const std::string name =
        channels.Unprefixed(event.channel) + "_" + std::to_string(count[event.channel]++);
    Write("server_commands", name, fuzz::EncodeRecord(found->second, event.data));
    if (event.channel == channels.status) continue;
    in_order.push_back(fuzz::EncodeRecord(found->second | 0x80, event.data));
    Bytes envelope = {1, 0, 0, 0, 0};  // signed with the server's first key, dated now
    envelope.insert(envelope.end(), event.data.begin(), event.data.end());
    Write("signed_commands", name, fuzz::EncodeRecord(found->second, envelope));
    signed_in_order.push_back(fuzz::EncodeRecord(found->second | 0x80, envelope));
  }
  Write("server_commands", "session", Concatenated(in_order));
  Write("signed_commands", "session", Concatenated(signed_in_order));

  // What flagctl sends that the session did not.
  int64_t sequence = 100;
  std::vector<std::pair<std::string, std::pair<uint8_t, Bytes>>> more;
  const auto add = [&](const std::string& name, uint8_t channel, const Bytes& bytes) {
    more.push_back({name, {channel, bytes}});
  };
  for (const auto& [name, operation] :
       std::vector<std::pair<std::string, int8_t>>{{"rotate_x", camera_command_t::ROTATE_X},
                                                   {"rotate_y", camera_command_t::ROTATE_Y},
                                                   {"rotate_z", camera_command_t::ROTATE_Z},
                                                   {"reset", camera_command_t::RESET}}) {
    camera_command_t camera = Camera(operation);
    camera.angle = 15 * kRadiansPerDegree;
    add("CAMERA_" + name, 2, Publisher::Encode(Stamped(camera, ++sequence)));
  }
  const auto camera_with = [&](const std::string& name, int8_t operation, std::array<double, 3> vector,
                               double factor) {
    camera_command_t camera = Camera(operation);
    for (int k = 0; k < 3; ++k) camera.vector[k] = vector[size_t(k)];
    camera.factor = factor;
    add("CAMERA_" + name, 2, Publisher::Encode(Stamped(camera, ++sequence)));
  };
  camera_with("translate", camera_command_t::TRANSLATE, {0.5, 0, -0.2}, 1);
  camera_with("scale", camera_command_t::SCALE, {0.8, 2.2, 0}, 1.5);
  camera_with("look_at", camera_command_t::LOOK_AT, {1, 2, 0}, 1);
  camera_with("zoom", camera_command_t::ZOOM, {0, 0, 0}, 2);
  camera_with("eye", camera_command_t::SET_EYE, {3, 2, 4}, 1);
  camera_command_t fov = Camera(camera_command_t::SET_FOV);
  fov.angle = 50 * kRadiansPerDegree;
  add("CAMERA_fov", 2, Publisher::Encode(Stamped(fov, ++sequence)));
  camera_command_t size = Camera(camera_command_t::SET_IMAGE_SIZE);
  size.width = 96;
  size.height = 64;
  add("CAMERA_size", 2, Publisher::Encode(Stamped(size, ++sequence)));
  add("PARAM_reset", 1, Publisher::Encode(Stamped(Param({}, true), ++sequence)));
  add("PARAM_grid", 1, Publisher::Encode(Stamped(Param({{"cols", "8"}, {"rows", "5"}}), ++sequence)));
  add("PARAM_integrator", 1,
      Publisher::Encode(Stamped(Param({{"integrator", "rk4"}, {"self_collision", "true"}}), ++sequence)));
  add("PARAM_frames", 1,
      Publisher::Encode(Stamped(Param({{"frame_rate", "15"}, {"shading", "phong"}}), ++sequence)));
  add("KEYFRAME_add_smooth", 3,
      Publisher::Encode(Stamped(KeyAdd(2, timeline_key_t::LAW_SMOOTH, true), ++sequence)));
  keyframe_command_t change = KeyAdd(1, timeline_key_t::LAW_STEP, false);
  change.operation = keyframe_command_t::CHANGE;
  change.time = 2;
  change.key.time = 2.5;
  add("KEYFRAME_change", 3, Publisher::Encode(Stamped(change, ++sequence)));
  keyframe_command_t remove = Keyframe(keyframe_command_t::REMOVE);
  remove.time = 2.5;
  add("KEYFRAME_remove", 3, Publisher::Encode(Stamped(remove, ++sequence)));
  keyframe_command_t seek = Keyframe(keyframe_command_t::SEEK);
  seek.time = 0.5;
  add("KEYFRAME_seek", 3, Publisher::Encode(Stamped(seek, ++sequence)));
  keyframe_command_t loop = Keyframe(keyframe_command_t::LOOP);
  loop.loop = true;
  add("KEYFRAME_loop", 3, Publisher::Encode(Stamped(loop, ++sequence)));
  keyframe_command_t speed = Keyframe(keyframe_command_t::SPEED);
  speed.speed = 2;
  add("KEYFRAME_speed", 3, Publisher::Encode(Stamped(speed, ++sequence)));
  add("KEYFRAME_pause", 3, Publisher::Encode(Stamped(Keyframe(keyframe_command_t::PAUSE), ++sequence)));
  add("KEYFRAME_clear", 3, Publisher::Encode(Stamped(Keyframe(keyframe_command_t::CLEAR), ++sequence)));
  std::vector<Bytes> timeline;
  for (const auto& [name, record] : more) {
    Write("server_commands", name, fuzz::EncodeRecord(record.first, record.second));
    if (name.rfind("KEYFRAME", 0) == 0)
      timeline.push_back(fuzz::EncodeRecord(record.first | 0x80, record.second));
  }
  // A timeline played, edited while it plays, then cleared.
  const Bytes add0 = Publisher::Encode(Stamped(KeyAdd(0, timeline_key_t::LAW_CUBIC, true), 1));
  const Bytes play = Publisher::Encode(Stamped(Keyframe(keyframe_command_t::PLAY), 2));
  timeline.insert(timeline.begin(), {fuzz::EncodeRecord(3, add0), fuzz::EncodeRecord(3 | 0x80, play)});
  Write("server_commands", "timeline", Concatenated(timeline));

  // The envelope's refusals: unsigned, another key, a key the server lacks, a spoiled MAC, a
  // stale date, and a signed command sent again byte for byte (a replay).
  const Bytes wind = Publisher::Encode(Stamped(Wind(5, 0, 1, 0.1, 0), 1));
  const auto envelope = [&wind](uint8_t how, int32_t offset_ms) {
    Bytes bytes = {how};
    for (int k = 0; k < 4; ++k) bytes.push_back(uint8_t(uint32_t(offset_ms) >> (8 * k)));
    bytes.insert(bytes.end(), wind.begin(), wind.end());
    return fuzz::EncodeRecord(0, bytes);
  };
  Write("signed_commands", "unsigned", envelope(0, 0));
  Write("signed_commands", "second_key", envelope(1 | 2, 0));
  Write("signed_commands", "unknown_key", envelope(1 | 4, 0));
  Write("signed_commands", "bad_mac", envelope(1 | 8 | (5 << 5), 0));
  Write("signed_commands", "stale", envelope(1, -45000));
  Write("signed_commands", "replayed", Concatenated({envelope(1, 0), envelope(16, 0)}));
}

/// The clients' target: one message of each channel they read, a keyframe's tiles with their
/// manifest, and the stream as it came.
void StreamSeeds(const std::vector<LogEvent>& events, const Channels& channels) {
  const std::map<std::string, uint8_t> selector = {
      {channels.state, 0},  {channels.tile, 1},     {channels.frame, 2}, {channels.params, 3},
      {channels.status, 4}, {channels.timeline, 5}, {channels.ack, 6}};
  std::map<std::string, bool> written;
  std::vector<Bytes> stream, keyframe;
  bool keyframe_done = false;
  for (const LogEvent& event : events) {
    const auto found = selector.find(event.channel);
    if (found == selector.end()) continue;
    const Bytes record = fuzz::EncodeRecord(found->second, event.data);
    if (!written[event.channel]) {
      Write("client_streams", channels.Unprefixed(event.channel), record);
      written[event.channel] = true;
    }
    if (stream.size() < 60) stream.push_back(record);
    if (!keyframe_done && (event.channel == channels.tile || event.channel == channels.frame)) {
      keyframe.push_back(record);
      keyframe_done = event.channel == channels.frame;
    }
  }
  Write("client_streams", "keyframe", Concatenated(keyframe));
  Write("client_streams", "stream", Concatenated(stream));
}

/// The checkpoint target: each CHECKPOINT of the session (the start, the keyframe request's).
void CheckpointSeeds(const std::vector<LogEvent>& events, const Channels& channels) {
  int count = 0;
  for (const LogEvent& event : events) {
    if (event.channel == channels.checkpoint)
      Write("checkpoint", "checkpoint_" + std::to_string(count++), event.data);
  }
}

/// The log targets: the whole recording, and the same cut inside its last event.
void LogSeeds(const std::string& log_path) {
  const Bytes log = ReadFile(log_path);
  Write("event_log", "session", log);
  Write("event_log", "cut_short", Bytes(log.begin(), log.end() - 100));
  Write("replay", "session", log);
}

/// A Foxglove client's messages as the gateway targets' records (gateway_session.hpp): a text
/// message, a service call and a client publish.
Bytes TextRecord(const json& message) { return fuzz::EncodeRecord(0, Text(message.dump())); }

Bytes CallRecord(uint32_t service, uint32_t id, const json& request) {
  std::string frame(1, char(gateway::kServiceCallRequest));
  gateway::AppendU32(&frame, service);
  gateway::AppendU32(&frame, id);
  gateway::AppendU32(&frame, 4);
  return fuzz::EncodeRecord(1, Text(frame + "json" + request.dump()));
}

Bytes PublishRecord(uint32_t channel, const json& message) {
  std::string frame(1, char(gateway::kClientMessageData));
  gateway::AppendU32(&frame, channel);
  return fuzz::EncodeRecord(1, Text(frame + message.dump()));
}

/// What a Foxglove client sends the gateway, as records: 0 text, 1 binary, 2 the clock moves.
void ProtocolSeeds() {
  using namespace gateway;
  const Bytes tick = fuzz::EncodeRecord(2, {5});
  const json subscribe = {{"op", "subscribe"},
                          {"subscriptions",
                           {{{"id", 1}, {"channelId", kParamsChannel}},
                            {{"id", 2}, {"channelId", kAcksChannel}},
                            {{"id", 3}, {"channelId", kTilesChannel}}}}};
  Write("gateway_protocol", "subscribe",
        Concatenated({TextRecord(subscribe), TextRecord({{"op", "unsubscribe"}, {"subscriptionIds", {2}}})}));
  Write(
      "gateway_protocol", "parameters",
      Concatenated(
          {TextRecord({{"op", "subscribeParameterUpdates"}, {"parameterNames", json::array()}}),
           TextRecord({{"op", "getParameters"}, {"parameterNames", {"stiffness", "cols"}}, {"id", "g1"}}),
           TextRecord({{"op", "setParameters"},
                       {"parameters",
                        {{{"name", "stiffness"}, {"value", 2500}}, {{"name", "shading"}, {"value", "flat"}}}},
                       {"id", "s1"}}),
           tick}));
  Write("gateway_protocol", "wind_service",
        Concatenated(
            {CallRecord(kWindService, 1, {{"velocity", {8, 0, 2}}, {"gust", 0.3}, {"ramp", 1}}), tick}));
  Write(
      "gateway_protocol", "set_service",
      Concatenated(
          {CallRecord(kSetService, 2, {{"parameters", {{"damping", 0.1}, {"relative_wind", true}}}}), tick}));
  Write("gateway_protocol", "camera_service",
        Concatenated(
            {CallRecord(kCameraService, 3, {{"operation", "orbit"}, {"degrees", 30}, {"degrees2", 10}}),
             CallRecord(kCameraService, 4, {{"operation", "size"}, {"width", 320}, {"height", 200}}),
             CallRecord(kCameraService, 5, {{"operation", "look_at"}, {"vector", {1, 2, 0}}}), tick}));
  Write("gateway_protocol", "keyframe_service",
        Concatenated(
            {CallRecord(kKeyframeService, 6,
                        {{"operation", "add"},
                         {"key",
                          {{"time", 0},
                           {"law", "cubic"},
                           {"wind", {{"velocity", {7, 0, 0}}, {"gust", 0.2}}},
                           {"parameters", {{"stiffness", 1500}}},
                           {"camera", {{"eye", {2.6, 1.9, 4.4}}, {"target", {0.8, 2.2, 0}}, {"fov", 40}}}}}}),
             CallRecord(kKeyframeService, 7, {{"operation", "play"}}),
             CallRecord(kKeyframeService, 8, {{"operation", "speed"}, {"speed", 2}}), tick}));
  Write("gateway_protocol", "refresh_record",
        Concatenated({CallRecord(kRefreshService, 9, json::object()),
                      CallRecord(kRecordService, 10, {{"action", "status"}}),
                      CallRecord(kRecordService, 11, {{"action", "start"}}), tick,
                      CallRecord(kRecordService, 12, {{"action", "stop"}})}));
  Write("gateway_protocol", "client_publish",
        Concatenated({TextRecord({{"op", "advertise"},
                                  {"channels",
                                   {{{"id", 7},
                                     {"topic", "/flag/wind"},
                                     {"encoding", "json"},
                                     {"schemaName", "flagsim.WindRequest"}}}}}),
                      PublishRecord(7, {{"velocity", {3, 0, 1}}}), tick,
                      TextRecord({{"op", "unadvertise"}, {"channelIds", {7}}})}));
}

/// The gateway of several servers: ALPHA_ in slot 1, BETA_ in slot 2 (ids 16 s + base); a
/// record with selector 3 is a STATUS of the server its byte picks (0 ALPHA_, 1 BETA_).
void GatewayServersSeeds() {
  using namespace gateway;
  const auto in = [](uint32_t slot, uint32_t base) { return IdIn(slot, base); };
  const Bytes tick = fuzz::EncodeRecord(2, {5});
  const Bytes silence = fuzz::EncodeRecord(2, {60});  // 6 s: both withdrawn
  const Bytes alpha_status = fuzz::EncodeRecord(3, {0});
  Write("gateway_servers", "subscribe_both",
        Concatenated({TextRecord({{"op", "subscribe"},
                                  {"subscriptions",
                                   {{{"id", 1}, {"channelId", in(1, kTilesChannel)}},
                                    {{"id", 2}, {"channelId", in(2, kTilesChannel)}},
                                    {{"id", 3}, {"channelId", in(2, kAcksChannel)}},
                                    {{"id", 4}, {"channelId", kServersChannel}}}}}),
                      tick}));
  Write("gateway_servers", "parameters",
        Concatenated({TextRecord({{"op", "getParameters"}, {"parameterNames", json::array()}, {"id", "g"}}),
                      TextRecord({{"op", "setParameters"},
                                  {"parameters", {{{"name", "/BETA_/stiffness"}, {"value", 2500}}}},
                                  {"id", "s"}}),
                      TextRecord({{"op", "setParameters"},
                                  {"parameters",
                                   {{{"name", "/ALPHA_/damping"}, {"value", 0.1}},
                                    {{"name", "/BETA_/damping"}, {"value", 0.1}}}},
                                  {"id", "mixed"}}),
                      tick}));
  Write("gateway_servers", "services",
        Concatenated(
            {CallRecord(in(1, kWindService), 1, {{"velocity", {8, 0, 2}}}),
             CallRecord(in(2, kCameraService), 2, {{"operation", "size"}, {"width", 320}, {"height", 200}}),
             CallRecord(in(2, kRecordService), 3, {{"action", "status"}}), tick}));
  Write("gateway_servers", "withdrawn_and_back",
        Concatenated({TextRecord({{"op", "subscribe"},
                                  {"subscriptions", {{{"id", 1}, {"channelId", in(1, kStateChannel)}}}}}),
                      silence, CallRecord(in(1, kWindService), 4, {{"velocity", {1, 0, 0}}}), alpha_status,
                      CallRecord(in(1, kWindService), 5, {{"velocity", {2, 0, 0}}}), tick}));
  Write("gateway_servers", "client_publish",
        Concatenated({TextRecord({{"op", "advertise"},
                                  {"channels",
                                   {{{"id", 7}, {"topic", "/ALPHA_/flag/wind"}, {"encoding", "json"}},
                                    {{"id", 8}, {"topic", "/flag/wind"}, {"encoding", "json"}}}}}),
                      PublishRecord(7, {{"velocity", {3, 0, 1}}}),
                      PublishRecord(8, {{"velocity", {3, 0, 1}}}), tick}));
}

/// The HTTP target: the first byte picks the access policy (http_request_fuzz.cpp), then the request.
void HttpSeeds() {
  const auto request = [](uint8_t policy, const std::string& text) {
    Bytes bytes = {policy};
    bytes.insert(bytes.end(), text.begin(), text.end());
    return bytes;
  };
  Write("http_request", "page", request(0, "GET / HTTP/1.1\r\nHost: 127.0.0.1:8080\r\n\r\n"));
  Write("http_request", "script",
        request(0, "GET /app.js HTTP/1.1\r\nHost: localhost:8080\r\nOrigin: http://localhost:8080\r\n\r\n"));
  Write("http_request", "token_query",
        request(1 | 2,
                "GET /?token=0123456789abcdef0123456789abcdef HTTP/1.1\r\nHost: flag.example:8080\r\n\r\n"));
  Write("http_request", "token_cookie",
        request(1 | 2,
                "HEAD /index.html HTTP/1.1\r\nHost: flag.example\r\nCookie: a=1; "
                "flagsim_token=0123456789abcdef0123456789abcdef\r\n\r\n"));
  Write("http_request", "upgrade",
        request(1 | 2 | 4,
                "GET / HTTP/1.1\r\nHost: flag.example:8080\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
                "Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\n"
                "Sec-WebSocket-Protocol: x, foxglove.websocket.v1\r\nOrigin: https://app.foxglove.dev\r\n"
                "Authorization: Bearer 0123456789abcdef0123456789abcdef\r\n\r\n"));
  Write("http_request", "recording",
        request(0, "GET /recordings/flagsim-20260101-000000.lcmlog HTTP/1.1\r\nHost: [::1]:8080\r\n\r\n"));
  Write("http_request", "post",
        request(0, "POST / HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Length: 4\r\n\r\nbody"));
}

/// The scene target: every preset and example scene, and one with --set assignments after a NUL.
void SceneSeeds(const fs::path& source) {
  for (const fs::directory_entry& entry : fs::directory_iterator(source / "scenes")) {
    if (entry.path().extension() == ".toml")
      Write("scene_file", entry.path().filename().string(), ReadFile(entry.path()));
  }
  Bytes with_set = ReadFile(source / "scenes" / "gale.toml");
  const Bytes assignments = Text(std::string(1, '\0') + "cols=16\nrows=12\nintegrator=xpbd\n");
  with_set.insert(with_set.end(), assignments.begin(), assignments.end());
  Write("scene_file", "gale_with_set", with_set);
}

/// The PNG target: RGB as flagsim writes it, and the other kinds a PNG may hold.
void PngSeeds() {
  const fs::path scratch =
      fs::temp_directory_path() / ("flagsim-corpus-" + std::to_string(getpid()) + ".png");
  std::vector<uint8_t> rgb(12 * 8 * 3);
  for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = uint8_t(i * 7);
  WritePng(scratch.string(), 12, 8, rgb.data());
  Write("png", "rgb_12x8.png", ReadFile(scratch));
  for (const auto& [name, format] :
       std::vector<std::pair<std::string, png_uint_32>>{{"gray_12x8.png", PNG_FORMAT_GRAY},
                                                        {"gray_alpha_12x8.png", PNG_FORMAT_GA},
                                                        {"rgba_12x8.png", PNG_FORMAT_RGBA},
                                                        {"rgb16_12x8.png", PNG_FORMAT_LINEAR_RGB}}) {
    png_image image{};
    image.version = PNG_IMAGE_VERSION;
    image.width = 12;
    image.height = 8;
    image.format = format;
    std::vector<uint8_t> pixels(PNG_IMAGE_SIZE(image));
    for (size_t i = 0; i < pixels.size(); ++i) pixels[i] = uint8_t(i * 5);
    png_image_write_to_file(&image, scratch.c_str(), 0, pixels.data(), 0, nullptr);
    Write("png", name, ReadFile(scratch));
  }
  fs::remove(scratch);
}

/// The design image target: the PNG target's seeds, and a JPEG (baseline, as libjpeg writes it).
void DesignImageSeeds() {
  for (const fs::directory_entry& entry : fs::directory_iterator(g_corpus / "png"))
    Write("design_image", entry.path().filename().string(), ReadFile(entry.path()));
  std::vector<uint8_t> rgb(12 * 8 * 3);
  for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = uint8_t(i * 11);
  const std::string jpeg = EncodeJpeg(rgb.data(), 12, 8, 90);
  Write("design_image", "rgb_12x8.jpg", Bytes(jpeg.begin(), jpeg.end()));
}

/// The key file target: one flagctl keygen writes, and one with two keys and comments.
void KeyFileSeeds() {
  const fs::path scratch =
      fs::temp_directory_path() / ("flagsim-corpus-" + std::to_string(getpid()) + ".key");
  fs::remove(scratch);
  WriteNewKeyFile(scratch.string(), "ops");
  Write("key_file", "keygen", ReadFile(scratch));
  fs::remove(scratch);
  Write(
      "key_file", "two_keys",
      Text(
          "# flagsim command keys\n\nalpha 000102030405060708090a0b0c0d0e0f101112131415161718191a1b1c1d1e1f\n"
          "  beta.2 FFEEDDCCBBAA99887766554433221100ffeeddccbbaa99887766554433221100  \n"));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: fuzz_make_corpus SOURCE_DIR   (rewrites SOURCE_DIR/tests/fuzz/corpus)\n");
    return 2;
  }
  fuzz::QuietLogs();
  const fs::path source = argv[1];
  g_corpus = source / "tests" / "fuzz" / "corpus";
  fs::remove_all(g_corpus);
  const Channels channels;
  const std::string log_path =
      (fs::temp_directory_path() / ("flagsim-corpus-" + std::to_string(getpid()))).string();
  RecordSession(log_path);
  const std::vector<LogEvent> events = ReadEvents(log_path);
  CommandSeeds(events, channels);
  StreamSeeds(events, channels);
  CheckpointSeeds(events, channels);
  LogSeeds(log_path);
  fs::remove(log_path);
  ProtocolSeeds();
  GatewayServersSeeds();
  HttpSeeds();
  SceneSeeds(source);
  PngSeeds();
  DesignImageSeeds();
  KeyFileSeeds();
  size_t files = 0, bytes = 0;
  for (const fs::directory_entry& entry : fs::recursive_directory_iterator(g_corpus)) {
    if (!entry.is_regular_file()) continue;
    ++files;
    bytes += entry.file_size();
  }
  std::printf("%s: %zu seeds, %zu bytes (%zu events recorded)\n", g_corpus.c_str(), files, bytes,
              events.size());
  return 0;
}
