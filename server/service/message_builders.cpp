#include "server/service/message_builders.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "server/scene/parameter_table.hpp"
#include "server/service/command_authenticator.hpp"
#include "server/sim/integrator.hpp"

namespace flagsim {

state_t MakeStateMessage(const Session& session, int64_t utime) {
  const FlagSimulation& simulation = session.simulation();
  const auto& model = simulation.model();
  const auto& state = simulation.state();
  state_t message{};
  message.utime = utime;
  message.step = state.step;
  message.sim_time = state.time;
  message.state_hash = static_cast<int64_t>(simulation.Hash());
  message.cols = model.cols;
  message.rows = model.rows;
  message.width = static_cast<float>(session.scene().sim.width);
  message.height = static_cast<float>(session.scene().sim.height);
  for (int k = 0; k < 3; ++k) message.pole_top[k] = model.pole_top[k];
  message.pole_radius = session.scene().sim.pole_radius;
  const sim::Vec3 wind = simulation.wind().Mean(state.time);
  for (int k = 0; k < 3; ++k) message.wind[k] = wind[k];
  message.wind_gust = simulation.wind().Gust(state.time);
  message.kinetic_energy = sim::KineticEnergy(model, state);
  const int n = state.num_nodes();
  message.num_values = 3 * n;
  message.position.resize(3 * n);
  for (int i = 0; i < n; ++i) {
    message.position[3 * i] = state.x[i];
    message.position[3 * i + 1] = state.y[i];
    message.position[3 * i + 2] = state.z[i];
  }
  return message;
}

double StateRate(const Session& session) {
  return session.simulation().sleeping() ? 1.0 : session.scene().service.state_rate;
}

FrameInfo MakeFrameInfo(const Session& session, int64_t utime) {
  FrameInfo info;
  info.utime = utime;
  info.step = session.simulation().state().step;
  info.sim_time = session.simulation().state().time;
  const render::Camera& camera = session.scene().camera;
  info.view = camera.View();
  info.projection = camera.Projection();
  info.camera_eye = camera.eye;
  info.camera_target = camera.target;
  info.camera_fov = camera.fov_y * 180 / M_PI;
  info.frame_rate = session.scene().service.frame_rate;
  return info;
}

params_t MakeParamsMessage(const Scene& scene, int64_t utime) {
  params_t message{};
  message.utime = utime;
  for (const Parameter& parameter : ParameterTable::Get().parameters()) {
    parameter_t row;
    row.name = parameter.name;
    row.unit = parameter.unit;
    row.kind = static_cast<int8_t>(parameter.kind);  // same order as parameter_t's constants
    row.min_value = parameter.min_value;
    row.max_value = parameter.max_value;
    row.default_value = parameter.default_value();
    row.value = parameter.get(scene);
    row.value_text = parameter.Format(row.value);
    row.choices = parameter.choices;
    row.num_choices = static_cast<int32_t>(row.choices.size());
    row.description = parameter.description;
    message.parameters.push_back(std::move(row));
  }
  message.num_parameters = static_cast<int32_t>(message.parameters.size());
  return message;
}

namespace {

timeline_key_t MakeKeyMessage(const sim::Keyframe& key) {
  timeline_key_t message{};
  message.time = key.time;
  message.law = static_cast<int8_t>(key.law);  // ControlLaw's order is the LAW_* constants'
  WriteControls(key.wind, key.parameters, key.camera, &message);
  return message;
}

}  // namespace

timeline_t MakeTimelineMessage(const sim::Timeline& timeline, int64_t step, int64_t utime) {
  timeline_t message{};
  message.utime = utime;
  message.step = step;
  message.playing = timeline.playing();
  message.position = timeline.position();
  message.speed = timeline.speed();
  message.loop = timeline.loop();
  message.last_key_time = timeline.End();
  message.gliding = timeline.gliding();
  for (const sim::Keyframe& key : timeline.keys()) message.keys.push_back(MakeKeyMessage(key));
  message.num_keys = static_cast<int32_t>(message.keys.size());
  return message;
}

status_t MakeStatusMessage(const Session& session, const ServerStats& stats, const StatusWindow& window,
                           int64_t utime) {
  const FlagSimulation& simulation = session.simulation();
  const auto per_second = [&](double count) {
    return window.wall_seconds > 0 ? count / window.wall_seconds : 0.0;
  };
  const auto mean_us = [](double seconds, int64_t count) { return count > 0 ? 1e6 * seconds / count : 0.0; };
  status_t message{};
  message.utime = utime;
  message.uptime = window.uptime;
  message.step = simulation.state().step;
  message.sim_time = simulation.state().time;
  message.real_time_factor = per_second(window.sim_seconds);
  message.steps_per_second = per_second(double(stats.steps));
  message.substeps = simulation.substeps();
  message.num_nodes = simulation.model().num_nodes();
  message.threads = simulation.params().threads;
  message.integrator = sim::IntegratorName(simulation.params().integrator);
  message.sleeping = simulation.sleeping();
  message.paused = session.paused();
  message.steps_owed = int32_t(session.steps_owed());
  message.time_scale = session.scene().service.time_scale;
  message.step_time_us = mean_us(stats.step_seconds, stats.steps);
  message.publish_time_us = mean_us(stats.publish_seconds, stats.states_published);
  message.state_rate_hz = per_second(double(stats.states_published));
  message.frame_rate_hz = per_second(double(stats.frames_published));
  message.render_time_us = mean_us(stats.render_seconds, stats.frames_published);
  message.encode_time_us = mean_us(stats.encode_seconds, stats.frames_published);
  const double frames = double(std::max<int64_t>(stats.frames_published, 1));
  message.tiles_per_frame = double(stats.tiles_published) / frames;
  message.frame_bytes = stats.tile_bytes / frames;
  message.frames_skipped = stats.frames_skipped;
  message.bytes_per_second = per_second(window.bytes);
  message.commands_accepted = stats.commands_accepted;
  message.commands_rejected = stats.commands_rejected;
  message.messages_dropped = stats.messages_dropped;
  using Refusal = CommandAuthenticator::Refusal;
  const auto refused = [&stats](Refusal refusal) { return stats.commands_refused[size_t(refusal)]; };
  message.commands_unsigned = refused(Refusal::kUnsigned);
  message.commands_unknown_key = refused(Refusal::kUnknownKey);
  message.commands_bad_mac = refused(Refusal::kBadMac);
  message.commands_replayed = refused(Refusal::kReplayed);
  message.commands_stale = refused(Refusal::kStale);
  message.recoveries = simulation.recoveries();
  message.last_recovery = simulation.last_guard_event().Describe();
  return message;
}

}  // namespace flagsim

namespace flagsim {
namespace {

std::string AutoChooses(const ModelSettings& model) {
  if (model.auto_integrator && model.auto_grid) return "integrator and grid";
  if (model.auto_integrator) return "integrator";
  if (model.auto_grid) return "grid";
  return "nothing";
}

std::string Number(const char* format, double value) {
  char text[64];
  std::snprintf(text, sizeof(text), format, value);
  return text;
}

}  // namespace

// auto everywhere: its choice and why. Set by the user: whether real time holds, and what auto
// would choose.
void WriteModelStatus(const Session& session, const std::optional<model::ModelDecisions>& decisions,
                      status_t* message) {
  const Scene& scene = session.scene();
  message->cols = scene.sim.cols;
  message->rows = scene.sim.rows;
  message->model_auto = AutoChooses(scene.model);
  message->screen_error_px = -1;
  message->model_cost = -1;
  message->model_note = "";
  if (decisions && decisions->in_force_estimated) {
    message->screen_error_px = decisions->in_force.error_px;
    message->model_cost = decisions->in_force.cost;
  }
  const bool all_auto = scene.model.auto_integrator && scene.model.auto_grid;
  // Behind: slower than the clock asks for (time_scale), while it runs.
  const double asked = scene.service.time_scale;
  const bool behind = !message->sleeping && !message->paused && message->real_time_factor > 0 &&
                      message->real_time_factor < 0.99 * asked;
  std::string note;
  if (!decisions) {
    note = "auto has not decided yet";
  } else if (all_auto) {
    note = "auto: " + model::Describe(decisions->chosen.kind) + " of " +
           Number("%g", scene.model.error_budget) + " px";
  } else {
    note = "set by the user: " + std::string(scene.model.auto_integrator ? "the grid" :
                                             scene.model.auto_grid ? "the integrator" : "the integrator and the grid") +
           "; auto would choose " + model::Describe(decisions->free);
  }
  if (behind && asked == 1) {
    note += "; real time not held: " + Number("%.2f", message->real_time_factor) + " of real time";
  } else if (behind) {
    note += "; time_scale " + Number("%g", asked) + " not held: " + Number("%.2f", message->real_time_factor) +
            " simulated s per s";
  }
  message->model_note = note;
}

}  // namespace flagsim
