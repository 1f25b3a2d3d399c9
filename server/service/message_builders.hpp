// Outgoing messages built from the session: STATE, PARAMS, STATUS, TIMELINE, and what a frame's
// manifest says of the session. Pure functions of what they read, so tests can check them
// without a bus.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "flagsim/params_t.hpp"
#include "flagsim/state_t.hpp"
#include "flagsim/status_t.hpp"
#include "flagsim/timeline_t.hpp"
#include "server/model/auto_model.hpp"
#include "server/service/server_stats.hpp"
#include "server/service/session.hpp"
#include "server/service/tile_stream.hpp"

namespace flagsim {

/// The flag's nodes now: positions, grid, pole, mean wind and gust strength, kinetic energy, hash.
state_t MakeStateMessage(const Session& session, int64_t utime);

/// STATE messages per second of simulated time: the scene's rate, or 1 Hz while the flag
/// sleeps (it does not move; once a second says so).
double StateRate(const Session& session);

/// The step, time and camera (matrices, eye, target, fov) of a frame drawn now, for its manifest.
FrameInfo MakeFrameInfo(const Session& session, int64_t utime);

/// The parameter table with the session's current values.
params_t MakeParamsMessage(const Scene& scene, int64_t utime);

/// The timeline: its keys (what each sets), play state and position; `step` the step it stands at.
/// Writes controls (a key's, or a glide's) into a message with the fields timeline_key_t and
/// controls_t share: has_wind, wind_velocity, wind_gust, names, values, has_camera, camera_*.
template <class Message>
void WriteControls(const std::optional<sim::WindControl>& wind,
                   const std::vector<sim::ParameterControl>& parameters,
                   const std::optional<sim::CameraControl>& camera, Message* message) {
  message->has_wind = wind.has_value();
  if (wind) {
    for (int k = 0; k < 3; ++k) message->wind_velocity[k] = wind->velocity[k];
    message->wind_gust = wind->gust;
  }
  for (const sim::ParameterControl& parameter : parameters) {
    message->names.push_back(parameter.name);
    message->values.push_back(parameter.value);
  }
  message->num_parameters = static_cast<int32_t>(message->names.size());
  message->has_camera = camera.has_value();
  if (camera) {
    for (int k = 0; k < 3; ++k) {
      message->camera_eye[k] = camera->eye[k];
      message->camera_target[k] = camera->target[k];
    }
    message->camera_fov = camera->fov;
  }
}

timeline_t MakeTimelineMessage(const sim::Timeline& timeline, int64_t step, int64_t utime);

/// What passed since the last STATUS.
struct StatusWindow {
  double wall_seconds = 0;  ///< s of wall time
  double sim_seconds = 0;   ///< s of simulated time
  double bytes = 0;         ///< bytes published
  double uptime = 0;        ///< s since the server started
};

/// Health over the window: rates, mean times, counters.
status_t MakeStatusMessage(const Session& session, const ServerStats& stats, const StatusWindow& window,
                           int64_t utime);

/// STATUS's model fields from auto's last decisions (none before the first) and the real-time
/// factor the message reports.
void WriteModelStatus(const Session& session, const std::optional<model::ModelDecisions>& decisions,
                      status_t* message);

}  // namespace flagsim
