// One populated instance of each message type, for round-trip and hostile-bytes tests.
#pragma once

#include <cstdint>
#include <vector>

#include "flagsim/ack_t.hpp"
#include "flagsim/camera_command_t.hpp"
#include "flagsim/frame_t.hpp"
#include "flagsim/keyframe_command_t.hpp"
#include "flagsim/param_command_t.hpp"
#include "flagsim/params_t.hpp"
#include "flagsim/refresh_request_t.hpp"
#include "flagsim/state_t.hpp"
#include "flagsim/status_t.hpp"
#include "flagsim/tile_t.hpp"
#include "flagsim/timeline_t.hpp"
#include "flagsim/wind_command_t.hpp"

namespace flagsim::testing {

template <class Message>
std::vector<uint8_t> Encode(const Message& message) {
  std::vector<uint8_t> bytes(static_cast<size_t>(message.getEncodedSize()));
  message.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

inline param_command_t SomeParamCommand() {
  param_command_t command{};
  command.utime = 1;
  command.client_id = "test-client";
  command.sequence = 7;
  command.names = {"stiffness", "integrator"};
  command.values = {"1500", "seed"};
  command.num_assignments = 2;
  return command;
}

inline wind_command_t SomeWindCommand() {
  wind_command_t command{};
  command.client_id = "test-client";
  command.sequence = 3;
  command.velocity[0] = 4;
  command.velocity[2] = 1;
  command.gust = 0.25;
  command.ramp_time = 1.5;
  return command;
}

inline state_t SomeState() {
  state_t state{};
  state.step = 42;
  state.cols = 3;
  state.rows = 2;
  state.num_values = 18;
  state.position.assign(18, 0.5f);
  state.state_hash = -5;
  state.wind[0] = 6;
  state.wind_gust = 0.2;
  state.kinetic_energy = 0.125;
  return state;
}

inline params_t SomeParams() {
  params_t params{};
  parameter_t row{};
  row.name = "integrator";
  row.kind = parameter_t::CHOICE;
  row.choices = {"a", "b"};
  row.num_choices = 2;
  row.value_text = "a";
  params.parameters = {row, row};
  params.num_parameters = 2;
  return params;
}

inline timeline_key_t SomeKey() {
  timeline_key_t key{};
  key.time = 2;
  key.law = timeline_key_t::LAW_SMOOTH;
  key.has_wind = true;
  key.wind_velocity[0] = 6;
  key.wind_gust = 0.2;
  key.names = {"stiffness", "damping"};
  key.values = {1500, 0.1};
  key.num_parameters = 2;
  key.has_camera = true;
  key.camera_eye[2] = 4;
  key.camera_target[1] = 2;
  key.camera_fov = 40;
  return key;
}

inline keyframe_command_t SomeKeyframeCommand() {
  keyframe_command_t command{};
  command.client_id = "k";
  command.sequence = 4;
  command.operation = keyframe_command_t::ADD;
  command.key = SomeKey();
  return command;
}

inline timeline_t SomeTimeline() {
  timeline_t timeline{};
  timeline.playing = true;
  timeline.position = 1.5;
  timeline.speed = 1;
  timeline.keys = {SomeKey(), SomeKey()};
  timeline.keys[1].time = 4;
  timeline.keys[1].num_parameters = 0;
  timeline.keys[1].names.clear();
  timeline.keys[1].values.clear();
  timeline.num_keys = 2;
  timeline.last_key_time = 4;
  return timeline;
}

inline tile_t SomeTile() {
  tile_t tile{};
  tile.width = 2;
  tile.height = 2;
  tile.data = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
  tile.num_bytes = 12;
  return tile;
}

inline frame_t SomeFrame() {
  frame_t frame{};
  frame.tile_indices = {0, 3, 4};
  frame.num_tiles = 3;
  frame.camera_eye[2] = 4.4;
  frame.camera_target[1] = 2.2;
  frame.camera_fov = 40;
  return frame;
}

}  // namespace flagsim::testing
