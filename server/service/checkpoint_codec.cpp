#include "server/service/checkpoint_codec.hpp"

#include <cmath>
#include <optional>

#include "common/printable_text.hpp"
#include "server/render/camera_moves.hpp"
#include "server/scene/parameter_table.hpp"
#include "server/scene/scene_timeline.hpp"
#include "server/service/command_apply.hpp"
#include "server/service/message_builders.hpp"

namespace flagsim {
namespace {

using Vec3 = sim::Vec3;

// ---- writing ---------------------------------------------------------------------------------

/// Every parameter of the table as `scene` holds it, by name.
void WriteParameters(const Scene& scene, std::vector<std::string>* names, std::vector<double>* values) {
  for (const Parameter& parameter : ParameterTable::Get().parameters()) {
    names->push_back(parameter.name);
    values->push_back(parameter.get(scene));
  }
}

controls_t MakeControls(const sim::Controls& controls) {
  controls_t message{};
  WriteControls(controls.wind, controls.parameters, controls.camera, &message);
  return message;
}

scene_t MakeSceneMessage(const Scene& scene) {
  scene_t message{};
  message.name = scene.name;
  message.seed = static_cast<int64_t>(scene.seed);
  message.settle = scene.settle;
  WriteParameters(scene, &message.names, &message.values);
  message.num_parameters = static_cast<int32_t>(message.names.size());
  for (int k = 0; k < 3; ++k) message.wind_velocity[k] = scene.wind.velocity[k];
  message.wind_gust = scene.wind.gust;
  message.wind_ramp_time = scene.wind.ramp_time;
  const render::Camera& camera = scene.camera;
  for (int k = 0; k < 3; ++k) {
    message.camera_eye[k] = camera.eye[k];
    message.camera_target[k] = camera.target[k];
    message.camera_up[k] = camera.up[k];
  }
  message.camera_fov_y = camera.fov_y;
  message.camera_near = camera.near_plane;
  message.camera_far = camera.far_plane;
  message.camera_width = camera.width;
  message.camera_height = camera.height;
  for (int i = 0; i < 16; ++i) message.camera_transform[i] = camera.scene.matrix()(i / 4, i % 4);
  if (const DesignFilePtr& image = scene.service.design_file) {
    message.design_file = image->digest;
    message.design_file_name = image->name;
  }
  message.width_follows_design = scene.service.width_follows_design;
  message.timeline = MakeTimelineMessage(scene.timeline, 0, 0);
  if (const auto& glide = scene.timeline.glide()) {
    message.glide_elapsed = glide->elapsed;
    message.glide_from = MakeControls(glide->from);
    message.glide_start = MakeControls(glide->start);
  }
  return message;
}

// ---- reading ---------------------------------------------------------------------------------

std::string Finite(const std::string& field, double value) {
  return std::isfinite(value) ? "" : field + ": " + std::to_string(value) + " is not a finite number";
}

std::string Vector(const std::string& field, const double (&value)[3], Vec3* out) {
  for (int k = 0; k < 3; ++k) {
    const std::string problem = Finite(field + "[" + std::to_string(k) + "]", value[k]);
    if (!problem.empty()) return problem;
    (*out)[k] = value[k];
  }
  return "";
}

/// "" if `value` may be parameter `parameter`'s: finite, within its range, whole where it must be.
std::string CheckValue(const Parameter& parameter, double value, const std::string& field) {
  if (!std::isfinite(value) || value < parameter.min_value || value > parameter.max_value ||
      (parameter.kind != ParameterKind::kReal && value != std::floor(value))) {
    return field + "." + parameter.name + ": " + std::to_string(value) + "; allowed " +
           parameter.AllowedText();
  }
  return "";
}

/// Every parameter of the table, each once, into `scene`.
std::string ReadParameters(const std::vector<std::string>& names, const std::vector<double>& values,
                           const std::string& field, Scene* scene) {
  const ParameterTable& table = ParameterTable::Get();
  if (names.size() != values.size() || names.size() != table.parameters().size()) {
    return field + ": " + std::to_string(names.size()) + " names and " + std::to_string(values.size()) +
           " values; allowed one each for the " + std::to_string(table.parameters().size()) + " parameters";
  }
  std::vector<bool> seen(table.parameters().size(), false);
  for (size_t i = 0; i < names.size(); ++i) {
    const Parameter* parameter = table.Find(names[i]);
    if (parameter == nullptr) return field + ": " + names[i] + " is not a parameter (see flagctl params)";
    const size_t index = size_t(parameter - table.parameters().data());
    if (seen[index]) return field + ": " + names[i] + " comes twice";
    seen[index] = true;
    const std::string problem = CheckValue(*parameter, values[i], field);
    if (!problem.empty()) return problem;
    parameter->set(*scene, values[i]);
  }
  return "";
}

std::string ReadControls(const controls_t& message, const std::string& field, sim::Controls* controls) {
  if (message.has_wind) {
    sim::WindControl wind;
    std::string problem = Vector(field + ".wind_velocity", message.wind_velocity, &wind.velocity);
    if (problem.empty()) problem = Finite(field + ".wind_gust", message.wind_gust);
    if (!problem.empty()) return problem;
    wind.gust = message.wind_gust;
    controls->wind = wind;
  }
  if (message.names.size() != message.values.size() ||
      message.names.size() > TimelineLimits::kMaxKeyParameters)
    return field + ".num_parameters: " + std::to_string(message.names.size()) + "; allowed 0 .. 64";
  for (size_t i = 0; i < message.names.size(); ++i) {
    const std::string problem = Finite(field + ".values[" + std::to_string(i) + "]", message.values[i]);
    if (!problem.empty()) return problem;
    if (ParameterTable::Get().Find(message.names[i]) == nullptr)
      return field + ".names[" + std::to_string(i) + "]: " + message.names[i] + " is not a parameter";
    controls->parameters.push_back({message.names[i], message.values[i]});
  }
  if (message.has_camera) {
    sim::CameraControl camera;
    std::string problem = Vector(field + ".camera_eye", message.camera_eye, &camera.eye);
    if (problem.empty()) problem = Vector(field + ".camera_target", message.camera_target, &camera.target);
    if (problem.empty()) problem = Finite(field + ".camera_fov", message.camera_fov);
    if (!problem.empty()) return problem;
    camera.fov = message.camera_fov;
    controls->camera = camera;
  }
  return "";
}

/// The timeline's keys and play state, and the glide under way, checked against `scene`.
std::string ReadTimeline(const scene_t& message, const std::string& field, Scene* scene) {
  const timeline_t& wire = message.timeline;
  if (wire.keys.size() > TimelineLimits::kMaxKeys)
    return field + ".timeline.num_keys: " + std::to_string(wire.keys.size()) + "; allowed 0 .. 256";
  sim::Timeline timeline;
  for (size_t i = 0; i < wire.keys.size(); ++i) {
    sim::Keyframe key;
    const std::string problem = KeyOf(wire.keys[i], true, &key);
    if (!problem.empty()) return field + ".timeline.keys[" + std::to_string(i) + "]: " + problem;
    timeline.Add(key);
  }
  std::string problem = Finite(field + ".timeline.position", wire.position);
  if (problem.empty()) problem = CheckTimelineSpeed(field + ".timeline.speed", wire.speed);
  if (!problem.empty()) return problem;
  timeline.Seek(wire.position);
  timeline.SetSpeed(wire.speed);
  timeline.SetLoop(wire.loop);
  if (wire.playing) timeline.Play();
  if (wire.gliding) {
    sim::Timeline::Glide glide;
    problem = Finite(field + ".glide_elapsed", message.glide_elapsed);
    if (problem.empty()) problem = ReadControls(message.glide_from, field + ".glide_from", &glide.from);
    if (problem.empty()) problem = ReadControls(message.glide_start, field + ".glide_start", &glide.start);
    if (!problem.empty()) return problem;
    glide.elapsed = message.glide_elapsed;
    timeline.RestoreGlide(glide);
  }
  problem = CheckTimeline(timeline, *scene);
  if (!problem.empty()) return field + ".timeline: " + problem;
  scene->timeline = std::move(timeline);
  return "";
}

std::string ReadCamera(const scene_t& message, const std::string& field, render::Camera* camera) {
  std::string problem;
  Vec3 eye, target, up;
  problem = Vector(field + ".camera_eye", message.camera_eye, &eye);
  if (problem.empty()) problem = Vector(field + ".camera_target", message.camera_target, &target);
  if (problem.empty()) problem = Vector(field + ".camera_up", message.camera_up, &up);
  for (const auto& [name, value] : {std::pair{"camera_fov_y", message.camera_fov_y},
                                    {"camera_near", message.camera_near},
                                    {"camera_far", message.camera_far}}) {
    if (problem.empty()) problem = Finite(field + "." + name, value);
  }
  for (int i = 0; i < 16 && problem.empty(); ++i)
    problem = Finite(field + ".camera_transform[" + std::to_string(i) + "]", message.camera_transform[i]);
  if (!problem.empty()) return problem;
  using Move = render::CameraMove;
  if (message.camera_width < Move::kMinSize || message.camera_width > Move::kMaxWidth ||
      message.camera_height < Move::kMinSize || message.camera_height > Move::kMaxHeight) {
    return field + ".camera size: " + std::to_string(message.camera_width) + " x " +
           std::to_string(message.camera_height) + " px; allowed " + std::to_string(Move::kMinSize) + " .. " +
           std::to_string(Move::kMaxWidth) + " x " + std::to_string(Move::kMinSize) + " .. " +
           std::to_string(Move::kMaxHeight);
  }
  if (!(message.camera_fov_y > 0 && message.camera_fov_y < M_PI && message.camera_near > 0 &&
        message.camera_far > message.camera_near)) {
    return field + ".camera: fov_y in (0, pi) rad and 0 < near < far allowed";
  }
  camera->eye = Eigen::Vector3d(eye[0], eye[1], eye[2]);
  camera->target = Eigen::Vector3d(target[0], target[1], target[2]);
  camera->up = Eigen::Vector3d(up[0], up[1], up[2]);
  camera->fov_y = message.camera_fov_y;
  camera->near_plane = message.camera_near;
  camera->far_plane = message.camera_far;
  camera->width = message.camera_width;
  camera->height = message.camera_height;
  for (int i = 0; i < 16; ++i) camera->scene.matrix()(i / 4, i % 4) = message.camera_transform[i];
  return "";
}

/// The design's image the scene names, from `designs`; "" or what is missing.
std::string ReadDesignFile(const scene_t& message, const std::string& field, const DesignLibrary* designs,
                           Scene* scene) {
  const bool image = scene->service.design == render::FlagDesign::kImage;
  if (message.design_file.empty()) return image ? field + ".design_file: design=image names no image" : "";
  if (!image) return field + ".design_file: an image is named, but the design is not image";
  scene->service.design_file = designs != nullptr ? designs->Find(message.design_file) : nullptr;
  if (!scene->service.design_file)
    return field + ".design_file: the image " + PrintableText(message.design_file_name, 128) + " (SHA-256 " +
           PrintableText(message.design_file, 64) +
           ") is not at hand: a recording holds it on DESIGN_FILE before the checkpoint";
  return "";
}

std::string ReadScene(const scene_t& message, const std::string& field, const DesignLibrary* designs,
                      Scene* scene) {
  Scene read;
  read.name = message.name;
  read.seed = static_cast<uint64_t>(message.seed);
  if (!(message.settle >= 0 && message.settle <= Scene::kMaxSettle)) {
    return field + ".settle: " + std::to_string(message.settle) + " is out of range; allowed 0 .. " +
           std::to_string(int(Scene::kMaxSettle)) + " s";
  }
  read.settle = message.settle;
  std::string problem = ReadParameters(message.names, message.values, field + ".parameters", &read);
  if (problem.empty()) problem = Vector(field + ".wind_velocity", message.wind_velocity, &read.wind.velocity);
  read.wind.gust = message.wind_gust;
  read.wind.ramp_time = message.wind_ramp_time;
  if (problem.empty()) problem = ParameterTable::CheckWind(read.wind);
  if (problem.empty()) problem = ReadCamera(message, field, &read.camera);
  if (problem.empty()) problem = ReadDesignFile(message, field, designs, &read);
  read.service.width_follows_design = message.width_follows_design;
  if (problem.empty()) problem = ParameterTable::CheckConsistency(read);
  if (problem.empty()) problem = ReadTimeline(message, field, &read);
  if (!problem.empty()) return problem;
  *scene = std::move(read);
  return "";
}

std::string ReadWindField(const checkpoint_t& message, sim::WindFieldState* wind) {
  std::string problem = Vector("wind_from_velocity", message.wind_from_velocity, &wind->from.velocity);
  if (problem.empty()) problem = Vector("wind_to_velocity", message.wind_to_velocity, &wind->to.velocity);
  for (const auto& [name, value] : {std::pair{"wind_from_gust", message.wind_from_gust},
                                    {"wind_to_gust", message.wind_to_gust},
                                    {"wind_ramp_time", message.wind_ramp_time},
                                    {"wind_ramp_start", message.wind_ramp_start},
                                    {"wind_carried", message.wind_carried}}) {
    if (problem.empty()) problem = Finite(name, value);
  }
  wind->from.gust = message.wind_from_gust;
  wind->to.gust = message.wind_to_gust;
  wind->to.ramp_time = message.wind_ramp_time;
  wind->ramp_start = message.wind_ramp_start;
  wind->carried = message.wind_carried;
  wind->seed = static_cast<uint64_t>(message.wind_seed);
  return problem;
}

/// The flag's nodes: as many as the grid has, every one finite.
std::string ReadState(const checkpoint_t& message, int nodes, sim::ClothState<float>* state) {
  const std::vector<float>* arrays[6] = {&message.x,  &message.y,  &message.z,
                                         &message.vx, &message.vy, &message.vz};
  for (const std::vector<float>* array : arrays) {
    if (message.num_nodes != nodes || array->size() != size_t(nodes)) {
      return "num_nodes: " + std::to_string(message.num_nodes) + "; the grid of its parameters has " +
             std::to_string(nodes);
    }
    for (const float value : *array) {
      if (!std::isfinite(value)) return "state: a node's position or velocity is not finite";
    }
  }
  state->x = message.x;
  state->y = message.y;
  state->z = message.z;
  state->vx = message.vx;
  state->vy = message.vy;
  state->vz = message.vz;
  state->time = message.sim_time;
  state->step = message.step;
  return "";
}

node_vectors_t NodeVectorsMessage(const std::vector<float>& x, const std::vector<float>& y,
                                  const std::vector<float>& z) {
  node_vectors_t message{};
  message.num_nodes = static_cast<int32_t>(x.size());
  message.x = x;
  message.y = y;
  message.z = z;
  return message;
}

/// A vector per node, or none where `may_be_none`: the grid's count, every value finite.
std::string ReadNodeVectors(const node_vectors_t& message, const std::string& field, int nodes,
                            bool may_be_none, sim::NodeVectors<float>* out) {
  const bool none = message.num_nodes == 0 && may_be_none;
  const size_t size = none ? 0 : size_t(nodes);
  if ((!none && message.num_nodes != nodes) || message.x.size() != size || message.y.size() != size ||
      message.z.size() != size) {
    return field + ".num_nodes: " + std::to_string(message.num_nodes) + "; allowed " +
           (may_be_none ? "0 or " : "") + std::to_string(nodes) + ", the grid's nodes";
  }
  for (const std::vector<float>* values : {&message.x, &message.y, &message.z}) {
    for (const float value : *values) {
      if (!std::isfinite(value)) return field + ": a value is not finite";
    }
  }
  *out = {message.x, message.y, message.z};
  return "";
}

/// What the simulation carries between steps: the integrator's memory, the guard's rollback
/// point (an earlier step's, or none: this one) and the sleep watch.
std::string ReadCarried(const checkpoint_t& message, int nodes, sim::CarriedState<float>* out) {
  constexpr int kStepsToSleep = sim::Simulation<float>::kStepsToSleep;
  std::string problem =
      ReadNodeVectors(message.integrator_memory, "integrator_memory", nodes, true, &out->integrator);
  const bool rollback = message.rollback_positions.num_nodes != 0;
  sim::NodeVectors<float> positions, velocities;
  if (problem.empty())
    problem = ReadNodeVectors(message.rollback_positions, "rollback_positions", nodes, true, &positions);
  if (problem.empty())
    problem =
        ReadNodeVectors(message.rollback_velocities, "rollback_velocities", nodes, !rollback, &velocities);
  if (problem.empty() && rollback &&
      !(message.rollback_step >= 0 && message.rollback_step < message.step &&
        std::isfinite(message.rollback_sim_time) && message.rollback_sim_time <= message.sim_time))
    problem = "rollback_step, rollback_sim_time: allowed an earlier step and time than the checkpoint's";
  if (problem.empty() && (message.calm_steps < 0 || message.calm_steps >= kStepsToSleep))
    problem = "calm_steps: " + std::to_string(message.calm_steps) + "; allowed 0 .. " +
              std::to_string(kStepsToSleep - 1);
  if (problem.empty())
    problem =
        ReadNodeVectors(message.calm_start, "calm_start", nodes, message.calm_steps == 0, &out->calm_start);
  if (!problem.empty()) return problem;
  if (rollback) {
    out->rollback = {positions.x,
                     positions.y,
                     positions.z,
                     velocities.x,
                     velocities.y,
                     velocities.z,
                     message.rollback_sim_time,
                     message.rollback_step};
  }
  out->calm_steps = message.calm_steps;
  return "";
}

std::string ReadSimulation(const checkpoint_t& message, const Scene& scene,
                           sim::SimulationSnapshot<float>* out) {
  Scene in_use = scene;
  std::string problem = ReadParameters(message.sim_names, message.sim_values, "sim_parameters", &in_use);
  if (problem.empty()) problem = ReadWindField(message, &out->wind);
  constexpr int kMaxGuardFactor = sim::Simulation<float>::kMaxGuardFactor;
  // A session's checks keep a flag's substeps within kMaxSubsteps (the guard's factor apart).
  if (problem.empty() && (message.substeps < 1 || message.substeps > sim::kMaxSubsteps))
    problem = "substeps: " + std::to_string(message.substeps) + "; allowed 1 .. " +
              std::to_string(sim::kMaxSubsteps);
  if (problem.empty() && (message.guard_factor < 1 || message.guard_factor > kMaxGuardFactor))
    problem = "guard_factor: " + std::to_string(message.guard_factor) + "; allowed 1 .. " +
              std::to_string(kMaxGuardFactor);
  if (problem.empty() && (message.step < 0 || !std::isfinite(message.sim_time) || message.sim_time < 0))
    problem = "step, sim_time: allowed 0 and up";
  if (problem.empty()) problem = ReadState(message, in_use.sim.cols * in_use.sim.rows, &out->state);
  if (problem.empty() && sim::StateHash(out->state) != uint64_t(message.state_hash))
    problem = "state_hash: does not match the nodes' positions and velocities";
  if (problem.empty()) problem = ReadCarried(message, in_use.sim.cols * in_use.sim.rows, &out->carried);
  if (!problem.empty()) return problem;
  out->params = in_use.sim;
  out->substeps = message.substeps;
  out->guard_factor = message.guard_factor;
  out->good_steps = message.good_steps;
  out->recoveries = message.recoveries;
  out->sleeping = message.sleeping;
  return "";
}

}  // namespace

checkpoint_t MakeCheckpointMessage(const SessionSnapshot& snapshot, const std::string& reason,
                                   int64_t utime) {
  const sim::SimulationSnapshot<float>& simulation = snapshot.simulation;
  checkpoint_t message{};
  message.utime = utime;
  message.step = simulation.state.step;
  message.sim_time = simulation.state.time;
  message.state_hash = static_cast<int64_t>(sim::StateHash(simulation.state));
  message.reason = reason;
  message.scene = MakeSceneMessage(snapshot.scene);
  message.initial = MakeSceneMessage(snapshot.initial);
  Scene in_use = snapshot.scene;
  in_use.sim = simulation.params;
  WriteParameters(in_use, &message.sim_names, &message.sim_values);
  message.num_sim_parameters = static_cast<int32_t>(message.sim_names.size());
  const sim::WindFieldState& wind = simulation.wind;
  for (int k = 0; k < 3; ++k) {
    message.wind_from_velocity[k] = wind.from.velocity[k];
    message.wind_to_velocity[k] = wind.to.velocity[k];
  }
  message.wind_from_gust = wind.from.gust;
  message.wind_to_gust = wind.to.gust;
  message.wind_ramp_time = wind.to.ramp_time;
  message.wind_ramp_start = wind.ramp_start;
  message.wind_carried = wind.carried;
  message.wind_seed = static_cast<int64_t>(wind.seed);
  message.substeps = simulation.substeps;
  message.guard_factor = simulation.guard_factor;
  message.good_steps = simulation.good_steps;
  message.recoveries = simulation.recoveries;
  message.sleeping = simulation.sleeping;
  message.timeline_segment = snapshot.timeline_segment;
  message.substeps_fixed = snapshot.substeps_fixed;
  const sim::ClothState<float>& state = simulation.state;
  message.num_nodes = state.num_nodes();
  message.x = state.x;
  message.y = state.y;
  message.z = state.z;
  message.vx = state.vx;
  message.vy = state.vy;
  message.vz = state.vz;
  const sim::CarriedState<float>& carried = simulation.carried;
  const sim::NodeVectors<float>& memory = carried.integrator;
  message.integrator_memory = NodeVectorsMessage(memory.x, memory.y, memory.z);
  const sim::ClothState<float>& rollback = carried.rollback;
  const bool rolls_back = rollback.num_nodes() > 0;
  message.rollback_step = rolls_back ? rollback.step : state.step;
  message.rollback_sim_time = rolls_back ? rollback.time : state.time;
  message.rollback_positions = NodeVectorsMessage(rollback.x, rollback.y, rollback.z);
  message.rollback_velocities = NodeVectorsMessage(rollback.vx, rollback.vy, rollback.vz);
  message.calm_steps = carried.calm_steps;
  const sim::NodeVectors<float>& calm = carried.calm_start;
  message.calm_start = NodeVectorsMessage(calm.x, calm.y, calm.z);
  return message;
}

std::string ReadCheckpoint(const checkpoint_t& message, SessionSnapshot* snapshot,
                           const DesignLibrary* designs) {
  SessionSnapshot read;
  std::string problem = ReadScene(message.scene, "scene", designs, &read.scene);
  if (problem.empty()) problem = ReadScene(message.initial, "initial", designs, &read.initial);
  if (problem.empty()) problem = ReadSimulation(message, read.scene, &read.simulation);
  if (problem.empty() && message.timeline_segment < -1)
    problem = "timeline_segment: " + std::to_string(message.timeline_segment) + "; allowed -1 and up";
  if (!problem.empty()) return "checkpoint at step " + std::to_string(message.step) + ": " + problem;
  read.timeline_segment = message.timeline_segment;
  read.substeps_fixed = message.substeps_fixed;
  *snapshot = std::move(read);
  return "";
}

}  // namespace flagsim
