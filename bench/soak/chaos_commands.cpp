#include "bench/soak/chaos_commands.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace flagsim::soak {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kDegree = M_PI / 180;
constexpr double kLastKeyTime = 20;  ///< s: keys fall in 0 .. this

/// A parameter and the part of its range the soak draws from: what the machine holds in real
/// time (grids up to 48 x 36, steps of 1 ms and more, two threads), not all the server allows.
struct Region {
  const char* name;
  double low, high;
  bool integer = false;
};
constexpr std::array kRegions = {
    Region{"cols", 4, 48, true},
    Region{"rows", 3, 36, true},
    Region{"stiffness", 200, 8000},
    Region{"shear_stiffness", 0, 1000},
    Region{"bending_stiffness", 0, 0.005},
    Region{"damping", 0, 0.5},
    Region{"friction", 0, 0.9},
    Region{"wind_coefficient", 0.2, 3},
    Region{"gravity", 0, 15},
    Region{"mass", 0.05, 1},
    Region{"compression", 0, 1},
    Region{"pole_friction", 0, 1},
    Region{"thickness", 0.002, 0.01},
    Region{"imperfection", 0, 0.01},
    Region{"dt", 0.001, 0.004},
    Region{"substeps", 0, 16, true},
    Region{"solver_iterations", 1, 30, true},
    Region{"state_rate", 10, 120, true},
    Region{"frame_rate", 0, 60, true},
    Region{"threads", 1, 2, true},
};
constexpr std::array kIntegrators = {
    "symplectic_euler", "seed", "explicit_euler", "verlet", "rk4", "xpbd", "implicit_euler", "projective"};
constexpr std::array kShadings = {"wireframe", "flat", "gouraud", "phong"};
/// Parameters a key may set (scene_timeline.hpp), with the part of their range drawn from.
constexpr std::array kAnimatable = {
    Region{"stiffness", 500, 6000}, Region{"shear_stiffness", 0, 800}, Region{"bending_stiffness", 0, 0.004},
    Region{"damping", 0, 0.3},      Region{"friction", 0, 0.8},        Region{"wind_coefficient", 0.3, 2.5},
    Region{"gravity", 5, 12},
};
constexpr std::array<std::array<int, 2>, 5> kImageSizes = {
    {{160, 120}, {320, 240}, {640, 360}, {960, 540}, {1280, 720}}};

template <class Message>
ChaosCommand Made(ChaosKind kind, bool valid, std::string what, Message message) {
  return ChaosCommand{kind, valid, std::move(what), ChaosMessage(std::move(message))};
}

}  // namespace

const char* ChaosKindName(ChaosKind kind) {
  switch (kind) {
    case ChaosKind::kWind:
      return "wind";
    case ChaosKind::kParameters:
      return "parameters";
    case ChaosKind::kCamera:
      return "camera";
    case ChaosKind::kKeyframe:
      return "keyframe";
    case ChaosKind::kReset:
      return "reset";
    case ChaosKind::kKeyframeRequest:
      return "keyframe request";
    case ChaosKind::kQuestion:
      return "question";
  }
  return "?";
}

ChaosCommands::ChaosCommands(uint64_t seed, double invalid_fraction)
    : random_(seed), invalid_fraction_(invalid_fraction) {}

// kind by weight (out of 100) => valid or not => the command
ChaosCommand ChaosCommands::Next() {
  const bool valid = !Chance(invalid_fraction_);
  const int pick = Integer(0, 99);
  if (pick < 20) return Wind(valid);
  if (pick < 40) return Parameters(valid);
  if (pick < 60) return Camera(valid);
  if (pick < 80) return Keyframe(valid);
  if (pick < 83) return Reset();
  if (pick < 90) return KeyframeRequest(false);
  return KeyframeRequest(true);
}

ChaosCommand ChaosCommands::Wind(bool valid) {
  wind_command_t wind{};
  wind.velocity[0] = Uniform(-12, 12);
  wind.velocity[1] = Uniform(-3, 3);
  wind.velocity[2] = Uniform(-12, 12);
  wind.gust = Uniform(0, 0.6);
  wind.ramp_time = Uniform(0, 3);
  if (valid) return Made(ChaosKind::kWind, true, "wind", wind);
  switch (Integer(0, 4)) {
    case 0:
      wind.velocity[Integer(0, 2)] = kNaN;
      return Made(ChaosKind::kWind, false, "wind NaN", wind);
    case 1:
      wind.velocity[0] = 1e3;
      return Made(ChaosKind::kWind, false, "wind 1000 m/s", wind);
    case 2:
      wind.gust = 1.5;
      return Made(ChaosKind::kWind, false, "gust 1.5", wind);
    case 3:
      wind.ramp_time = -1;
      return Made(ChaosKind::kWind, false, "ramp -1 s", wind);
    default:
      wind.ramp_time = INFINITY;
      return Made(ChaosKind::kWind, false, "ramp infinite", wind);
  }
}

ChaosCommand ChaosCommands::Parameters(bool valid) {
  param_command_t command{};
  const int count = Integer(1, 3);
  for (int k = 0; k < count; ++k) {
    const int which = Integer(0, int(kRegions.size()) + 3);
    std::string name, value;
    if (which < int(kRegions.size())) {
      const Region& region = kRegions[which];
      name = region.name;
      const double drawn = Uniform(region.low, region.high);
      value = region.integer ? std::to_string(int(std::lround(drawn))) : std::to_string(drawn);
    } else if (which == int(kRegions.size())) {
      name = "integrator", value = kIntegrators[Integer(0, int(kIntegrators.size()) - 1)];
    } else if (which == int(kRegions.size()) + 1) {
      name = "shading", value = kShadings[Integer(0, int(kShadings.size()) - 1)];
    } else {
      name = Chance(0.5) ? "relative_wind" : "self_collision", value = Chance(0.5) ? "true" : "false";
    }
    const bool taken = std::find(command.names.begin(), command.names.end(), name) != command.names.end();
    if (taken) continue;  // each once: a name twice is a mistake of its own
    command.names.push_back(name);
    command.values.push_back(value);
  }
  std::string what = "set";
  if (!valid) {  // one bad assignment among good ones: the whole command is rejected
    static constexpr std::array<std::array<const char*, 2>, 6> kBad = {{{"stiffness", "nan"},
                                                                        {"cols", "100000"},
                                                                        {"colour", "red"},
                                                                        {"damping", "abc"},
                                                                        {"integrator", "warp"},
                                                                        {"dt", "-1"}}};
    const auto& bad = kBad[Integer(0, int(kBad.size()) - 1)];
    command.names.push_back(bad[0]);
    command.values.push_back(bad[1]);
    what = std::string("set ") + bad[0] + "=" + bad[1];
  }
  command.num_assignments = int32_t(command.names.size());
  return Made(ChaosKind::kParameters, valid, what, command);
}

ChaosCommand ChaosCommands::Camera(bool valid) {
  camera_command_t camera{};
  if (!valid) {
    switch (Integer(0, 4)) {
      case 0:
        camera.operation = camera_command_t::SET_FOV, camera.angle = 500 * kDegree;
        break;
      case 1:
        camera.operation = camera_command_t::SET_IMAGE_SIZE, camera.width = 9000, camera.height = 100;
        break;
      case 2:
        // Out of range whatever the scene's turn (under the ground is frame-dependent: a turned
        // scene may lift the same vector above it, so that case belongs to the valid moves' luck).
        camera.operation = camera_command_t::SET_EYE;
        camera.vector[0] = 1, camera.vector[1] = -2000, camera.vector[2] = 3;
        break;
      case 3:
        camera.operation = camera_command_t::ORBIT, camera.angle = kNaN;
        break;
      default:
        camera.operation = 99;
        break;
    }
    return Made(ChaosKind::kCamera, false, "camera, invalid " + std::to_string(camera.operation), camera);
  }
  camera.operation = int8_t(Integer(camera_command_t::ROTATE_X, camera_command_t::SET_FOV));
  switch (camera.operation) {
    case camera_command_t::ROTATE_X:
    case camera_command_t::ROTATE_Y:
    case camera_command_t::ROTATE_Z:
      camera.angle = Uniform(-0.3, 0.3);
      break;
    case camera_command_t::TRANSLATE:
      for (double& axis : camera.vector) axis = Uniform(-0.3, 0.3);
      break;
    case camera_command_t::SCALE:
      camera.factor = Uniform(0.8, 1.25);
      camera.vector[0] = 0.75, camera.vector[1] = 2.5;  // about the flag
      break;
    case camera_command_t::ORBIT:
      camera.angle = Uniform(-0.5, 0.5), camera.angle2 = Uniform(-0.2, 0.2);
      break;
    case camera_command_t::LOOK_AT:
      camera.vector[0] = Uniform(0, 1.5), camera.vector[1] = Uniform(1.5, 3),
      camera.vector[2] = Uniform(-0.5, 0.5);
      break;
    case camera_command_t::SET_IMAGE_SIZE: {
      const auto& size = kImageSizes[Integer(0, int(kImageSizes.size()) - 1)];
      camera.width = size[0], camera.height = size[1];
      break;
    }
    case camera_command_t::ZOOM:
      camera.factor = Uniform(0.7, 1.4);
      break;
    case camera_command_t::SET_EYE:
      camera.vector[0] = Uniform(-1, 4), camera.vector[1] = Uniform(0.5, 4), camera.vector[2] = Uniform(2, 6);
      break;
    case camera_command_t::SET_FOV:
      camera.angle = Uniform(25, 70) * kDegree;
      break;
    default:
      break;  // RESET
  }
  return Made(ChaosKind::kCamera, true, "camera " + std::to_string(camera.operation), camera);
}

timeline_key_t ChaosCommands::Key(double time) {
  timeline_key_t key{};
  key.time = time;
  key.law = int8_t(Integer(timeline_key_t::LAW_STEP, timeline_key_t::LAW_CUBIC));
  key.has_wind = Chance(0.6);
  if (key.has_wind) {
    key.wind_velocity[0] = Uniform(-10, 10), key.wind_velocity[2] = Uniform(-10, 10);
    key.wind_gust = Uniform(0, 0.5);
  }
  for (const Region& region : kAnimatable) {
    if (!Chance(0.3)) continue;
    key.names.push_back(region.name);
    key.values.push_back(Uniform(region.low, region.high));
  }
  key.num_parameters = int32_t(key.names.size());
  key.has_camera = Chance(0.3);
  if (key.has_camera) {
    key.camera_eye[0] = Uniform(0, 3), key.camera_eye[1] = Uniform(1, 3), key.camera_eye[2] = Uniform(3, 5);
    key.camera_target[0] = 0.8, key.camera_target[1] = 2.2;
    key.camera_fov = Uniform(30, 60);
  }
  return key;
}

ChaosCommand ChaosCommands::Keyframe(bool valid) {
  keyframe_command_t command{};
  if (!valid) {
    command.operation = keyframe_command_t::ADD;
    command.key = Key(Uniform(0, kLastKeyTime));
    switch (Integer(0, 4)) {
      case 0:
        command.key.time = kNaN;
        break;
      case 1:
        command.key.law = 9;
        break;
      case 2:
        command.key.names.push_back("cols");  // the grid cannot be animated
        command.key.values.push_back(40);
        command.key.num_parameters = int32_t(command.key.names.size());
        break;
      case 3:
        command.operation = keyframe_command_t::SPEED, command.speed = 0;
        break;
      default:
        command.operation = 77;
        break;
    }
    return Made(ChaosKind::kKeyframe, false, "keyframe, invalid", command);
  }
  command.operation = int8_t(Integer(keyframe_command_t::ADD, keyframe_command_t::CHANGE));
  const bool about_a_key =
      command.operation == keyframe_command_t::REMOVE || command.operation == keyframe_command_t::CHANGE;
  if (about_a_key && key_times_.empty()) command.operation = keyframe_command_t::ADD;
  const size_t known = key_times_.empty() ? 0 : size_t(Integer(0, int(key_times_.size()) - 1));
  const double known_time = key_times_.empty() ? 0 : key_times_[known];
  switch (command.operation) {
    case keyframe_command_t::ADD:
      command.key = Key(std::round(Uniform(0, kLastKeyTime) * 4) / 4);
      if (std::find(key_times_.begin(), key_times_.end(), command.key.time) == key_times_.end())
        key_times_.push_back(command.key.time);
      break;
    case keyframe_command_t::REMOVE:
      command.time = known_time;
      key_times_.erase(key_times_.begin() + long(known));
      break;
    case keyframe_command_t::CHANGE:
      command.time = known_time;
      command.key = Key(known_time);
      command.keep_law = Chance(0.5);
      break;
    case keyframe_command_t::CLEAR:
      key_times_.clear();
      break;
    case keyframe_command_t::SEEK:
      command.time = Uniform(0, kLastKeyTime);
      break;
    case keyframe_command_t::LOOP:
      command.loop = Chance(0.5);
      break;
    case keyframe_command_t::SPEED:
      command.speed = Uniform(0.25, 4);
      break;
    default:
      break;  // PLAY, PAUSE
  }
  return Made(ChaosKind::kKeyframe, true, "keyframe " + std::to_string(command.operation), command);
}

ChaosCommand ChaosCommands::Reset() {
  param_command_t reset{};
  reset.reset_to_scene = true;
  key_times_.clear();
  return Made(ChaosKind::kReset, true, "reset", reset);
}

ChaosCommand ChaosCommands::KeyframeRequest(bool tables_only) {
  refresh_request_t request{};
  request.tables_only = tables_only;
  return Made(tables_only ? ChaosKind::kQuestion : ChaosKind::kKeyframeRequest, true,
              tables_only ? "question" : "keyframe request", request);
}

}  // namespace flagsim::soak
