#include "tests/fuzz/corpus_session.hpp"

#include <cmath>

#include "client/command_client.hpp"
#include "client/design_upload.hpp"
#include "client/log_recorder.hpp"
#include "messages/bus.hpp"
#include "messages/channels.hpp"
#include "server/service/server.hpp"
#include "tests/common/test_images.hpp"
#include "tests/fuzz/command_server.hpp"

namespace flagsim::fuzz {
namespace {
constexpr double kRadiansPerDegree = M_PI / 180;
}  // namespace

time_command_t Time(int8_t operation, int32_t steps) {
  time_command_t command{};
  command.operation = operation;
  command.steps = steps;
  return command;
}

Scene SessionScene() {
  Scene scene = fuzz::SmallScene();
  scene.camera.width = 160;
  scene.camera.height = 96;
  scene.service.frame_rate = 10;
  scene.service.state_rate = 20;
  return scene;
}

wind_command_t Wind(double vx, double vy, double vz, double gust, double ramp) {
  wind_command_t wind{};
  wind.velocity[0] = vx;
  wind.velocity[1] = vy;
  wind.velocity[2] = vz;
  wind.gust = gust;
  wind.ramp_time = ramp;
  return wind;
}

param_command_t Param(const std::vector<std::pair<std::string, std::string>>& assignments, bool reset) {
  param_command_t param{};
  param.reset_to_scene = reset;
  for (const auto& [name, value] : assignments) {
    param.names.push_back(name);
    param.values.push_back(value);
  }
  param.num_assignments = int32_t(param.names.size());
  return param;
}

camera_command_t Camera(int8_t operation) {
  camera_command_t camera{};
  camera.operation = operation;
  camera.factor = 1;
  return camera;
}

keyframe_command_t Keyframe(int8_t operation) {
  keyframe_command_t keyframe{};
  keyframe.operation = operation;
  keyframe.speed = 1;
  return keyframe;
}

keyframe_command_t KeyAdd(double time, int8_t law, bool camera) {
  keyframe_command_t add = Keyframe(keyframe_command_t::ADD);
  add.key.time = time;
  add.key.law = law;
  add.key.has_wind = true;
  add.key.wind_velocity[0] = 7 - 3 * time;
  add.key.wind_velocity[2] = 2 * time;
  add.key.wind_gust = 0.2;
  add.key.names = {"stiffness", "damping"};
  add.key.values = {1500 + 1000 * time, 0.05};
  add.key.num_parameters = 2;
  add.key.has_camera = camera;
  if (camera) {
    const double eye[3] = {2.6, 1.9, 4.4}, target[3] = {0.8, 2.2, 0};
    for (int k = 0; k < 3; ++k) {
      add.key.camera_eye[k] = eye[k] + time;
      add.key.camera_target[k] = target[k];
    }
    add.key.camera_fov = 40;
  }
  return add;
}

refresh_request_t Question() {
  refresh_request_t question{};
  question.tables_only = true;
  return question;
}

void RecordSession(const std::string& log_path) {
  Bus bus("memq://");
  const Channels channels;
  double now = 0;
  ServerOptions options;
  options.clock = [&now] { return now; };
  Server server(bus, channels, SessionScene(), options);
  LogRecorder recorder(bus, channels, log_path);
  CommandClient client(bus, channels, 5.0);
  client.WhileWaiting([&] {
    now += 1.0 / 240;
    server.Tick(now);
    server.DrainFrames();
  });
  client.Send(channels.refresh, refresh_request_t{});
  client.Send(channels.wind, Wind(8, 0, 2, 0.3, 0.5));
  client.Send(channels.param, Param({{"stiffness", "1500"}, {"damping", "0.1"}}));
  camera_command_t orbit = Camera(camera_command_t::ORBIT);
  orbit.angle = 30 * kRadiansPerDegree;
  orbit.angle2 = 10 * kRadiansPerDegree;
  client.Send(channels.camera, orbit);
  client.Send(channels.keyframe, KeyAdd(0, timeline_key_t::LAW_CUBIC, true));
  client.Send(channels.keyframe, KeyAdd(1, timeline_key_t::LAW_LINEAR, false));
  client.Send(channels.keyframe, Keyframe(keyframe_command_t::PLAY));
  client.Send(channels.time, Time(time_command_t::STEP, 3));
  client.Send(channels.time, Time(time_command_t::RESUME));
  client.Send(channels.refresh, Question());
  client.Send(channels.param, Param({{"stiffness", "bogus"}}));  // rejected: an ACK with a reason
  std::vector<uint8_t> pennant = testing::SolidRgba(12, 6, 200, 30, 40);
  for (size_t i = 3; i < pennant.size(); i += 16) pennant[i] = 0;  // some pixels transparent
  SendDesignFile(client, channels.design, "pennant.png", testing::PngBytes(12, 6, pennant));
  for (int tick = 0; tick < 60; ++tick) {  // 0.25 s more of the clock: states, frames, the timeline
    now += 1.0 / 240;
    server.Tick(now);
    server.DrainFrames();
    bus.HandleAll();
  }
}

std::vector<LogEvent> ReadEvents(const std::string& log_path) {
  EventLogReader reader(log_path);
  std::vector<LogEvent> events;
  LogEvent event;
  while (reader.Next(&event)) events.push_back(event);
  return events;
}

}  // namespace flagsim::fuzz
