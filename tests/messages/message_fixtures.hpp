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
  params.params = {row, row};
  params.num_params = 2;
  return params;
}

inline keyframe_command_t SomeKeyframeCommand() {
  keyframe_command_t command{};
  command.client_id = "k";
  command.operation = keyframe_command_t::ADD;
  command.names = {"stiffness"};
  command.values = {"100"};
  command.num_assignments = 1;
  return command;
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
  return frame;
}

}  // namespace flagsim::testing
