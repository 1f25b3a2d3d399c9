#include "server/service/command_apply.hpp"

#include <algorithm>

#include "common/printable_text.hpp"
#include "flagsim/refresh_request_t.hpp"
#include "messages/checked_decode.hpp"
#include "server/scene/scene_timeline.hpp"
#include "server/sim/integrator.hpp"

namespace flagsim {
namespace {

constexpr size_t kMaxCommandBytes = 64 * 1024;

// CameraMoveOf copies the operation code: the renderer's moves are numbered as CAMERA's.
static_assert(render::CameraMove::kRotateX == camera_command_t::ROTATE_X &&
              render::CameraMove::kRotateY == camera_command_t::ROTATE_Y &&
              render::CameraMove::kRotateZ == camera_command_t::ROTATE_Z &&
              render::CameraMove::kTranslate == camera_command_t::TRANSLATE &&
              render::CameraMove::kScale == camera_command_t::SCALE &&
              render::CameraMove::kOrbit == camera_command_t::ORBIT &&
              render::CameraMove::kLookAt == camera_command_t::LOOK_AT &&
              render::CameraMove::kSetImageSize == camera_command_t::SET_IMAGE_SIZE &&
              render::CameraMove::kReset == camera_command_t::RESET &&
              render::CameraMove::kZoom == camera_command_t::ZOOM &&
              render::CameraMove::kSetEye == camera_command_t::SET_EYE &&
              render::CameraMove::kSetFov == camera_command_t::SET_FOV &&
              render::CameraMove::kFrame == camera_command_t::FRAME &&
              render::CameraMove::kZoomAt == camera_command_t::ZOOM_AT);

/// The timeline operation a KEYFRAME operation code names.
std::optional<TimelineEdit::Operation> OperationOf(int8_t operation) {
  switch (operation) {
    case keyframe_command_t::ADD:
      return TimelineEdit::kAdd;
    case keyframe_command_t::CHANGE:
      return TimelineEdit::kChange;
    case keyframe_command_t::REMOVE:
      return TimelineEdit::kRemove;
    case keyframe_command_t::CLEAR:
      return TimelineEdit::kClear;
    case keyframe_command_t::PLAY:
      return TimelineEdit::kPlay;
    case keyframe_command_t::PAUSE:
      return TimelineEdit::kPause;
    case keyframe_command_t::SEEK:
      return TimelineEdit::kSeek;
    case keyframe_command_t::LOOP:
      return TimelineEdit::kLoop;
    case keyframe_command_t::SPEED:
      return TimelineEdit::kSpeed;
    default:
      return std::nullopt;
  }
}

/// Decodes `data` as a Command and applies it with `apply`; "" or why not.
template <class Command, class Apply>
std::string DecodeAndApply(const std::vector<uint8_t>& data, Apply apply) {
  std::string error;
  const std::optional<Command> command =
      wire::CheckedDecode<Command>(data.data(), data.size(), kMaxCommandBytes, &error);
  if (!command) return "undecodable: " + error;
  return apply(*command);
}

}  // namespace

sim::WindSettings WindOf(const wind_command_t& command) {
  sim::WindSettings wind;
  wind.velocity = {command.velocity[0], command.velocity[1], command.velocity[2]};
  wind.gust = command.gust;
  wind.ramp_time = command.ramp_time;
  return wind;
}

ParamChange ParamChangeOf(const param_command_t& command) {
  ParamChange change;
  change.reset_to_scene = command.reset_to_scene;
  for (size_t i = 0; i < command.names.size() && i < command.values.size(); ++i) {
    change.assignments.emplace_back(command.names[i], command.values[i]);
  }
  return change;
}

render::CameraMove CameraMoveOf(const camera_command_t& command) {
  render::CameraMove move;
  move.operation = command.operation;
  move.angle = command.angle;
  move.angle2 = command.angle2;
  move.vector = Eigen::Vector3d(command.vector[0], command.vector[1], command.vector[2]);
  move.factor = command.factor;
  move.width = command.width;
  move.height = command.height;
  return move;
}

std::string TimelineEditOf(const keyframe_command_t& command, TimelineEdit* edit) {
  const std::optional<TimelineEdit::Operation> operation = OperationOf(command.operation);
  if (!operation) {
    return "operation: " + std::to_string(command.operation) +
           " is not known; allowed 1 ADD, 2 REMOVE, 3 CLEAR, 4 PLAY, 5 PAUSE, 6 SEEK, 7 LOOP, 8 SPEED, 9 "
           "CHANGE";
  }
  edit->operation = *operation;
  edit->time = command.time;
  edit->speed = command.speed;
  edit->loop = command.loop;
  edit->keep_law = command.keep_law;
  if (edit->operation == TimelineEdit::kAdd || edit->operation == TimelineEdit::kChange) {
    const bool law = !(edit->operation == TimelineEdit::kChange && command.keep_law);
    return KeyOf(command.key, law, &edit->key);
  }
  return "";
}

std::string KeyOf(const timeline_key_t& message, bool law, sim::Keyframe* key) {
  if (law && (message.law < timeline_key_t::LAW_STEP || message.law > timeline_key_t::LAW_CUBIC)) {
    return "key.law: " + std::to_string(message.law) +
           " is not a law; allowed 0 (step), 1 (linear), 2 (smooth), 3 (cubic)";
  }
  if (message.num_parameters < 0 || size_t(message.num_parameters) > TimelineLimits::kMaxKeyParameters) {
    return "key.num_parameters: " + std::to_string(message.num_parameters) + "; allowed 0 .. " +
           std::to_string(TimelineLimits::kMaxKeyParameters);
  }
  key->time = message.time;
  if (law) key->law = static_cast<sim::ControlLaw>(message.law);
  if (message.has_wind) {
    key->wind = sim::WindControl{
        {message.wind_velocity[0], message.wind_velocity[1], message.wind_velocity[2]}, message.wind_gust};
  }
  for (size_t i = 0; i < message.names.size() && i < message.values.size(); ++i) {
    if (message.names[i].size() > kMaxNameLength) {
      return "key.names[" + std::to_string(i) + "]: " + std::to_string(message.names[i].size()) +
             " characters; allowed up to " + std::to_string(kMaxNameLength);
    }
    key->parameters.push_back({message.names[i], message.values[i]});
  }
  if (message.has_camera) {
    const auto& eye = message.camera_eye;
    const auto& target = message.camera_target;
    key->camera =
        sim::CameraControl{{eye[0], eye[1], eye[2]}, {target[0], target[1], target[2]}, message.camera_fov};
  }
  return "";
}

std::string ModelSwitchOf(const model_t& message, ModelSwitch* model) {
  const std::vector<std::string>& names = sim::IntegratorNames();
  const auto name = std::find(names.begin(), names.end(), message.integrator);
  if (name == names.end()) {
    return "integrator: '" + PrintableText(message.integrator) + "' is not an integrator";
  }
  model->integrator = static_cast<sim::IntegratorKind>(name - names.begin());
  model->solver_iterations = message.solver_iterations;
  model->cols = message.cols;
  model->rows = message.rows;
  return "";
}

model_t ModelMessageOf(const model::ModelDecision& decision, int64_t utime) {
  model_t message{};
  message.utime = utime;
  message.integrator = sim::IntegratorName(decision.integrator);
  message.solver_iterations = decision.solver_iterations;
  message.cols = decision.cols;
  message.rows = decision.rows;
  message.substeps = decision.substeps;
  message.error_px = decision.error_px;
  message.time_error_px = decision.time_px;
  message.resolution_error_px = decision.resolution_px;
  message.cost = decision.cost;
  message.choice = model::Describe(decision.kind);
  return message;
}

std::string TimeControlOf(const time_command_t& command, TimeControl* control) {
  switch (command.operation) {
    case time_command_t::PAUSE:
      control->operation = TimeControl::kPause;
      return "";
    case time_command_t::RESUME:
      control->operation = TimeControl::kResume;
      return "";
    case time_command_t::STEP:
      control->operation = TimeControl::kStep;
      control->steps = command.steps;
      return "";
    default:
      return "operation: " + std::to_string(int(command.operation)) +
             " is not an operation; allowed 1 (PAUSE), " + "2 (RESUME), 3 (STEP)";
  }
}

std::string ApplyCommandBytes(const std::string& channel, const std::vector<uint8_t>& data, Session* session,
                              const DesignLibrary* designs) {
  if (channel == "WIND") {
    return DecodeAndApply<wind_command_t>(data, [&](const auto& c) { return session->ApplyWind(WindOf(c)); });
  }
  if (channel == "PARAM") {
    return DecodeAndApply<param_command_t>(
        data, [&](const auto& c) { return session->ApplyParams(ParamChangeOf(c)); });
  }
  if (channel == "CAMERA") {
    return DecodeAndApply<camera_command_t>(
        data, [&](const auto& c) { return session->ApplyCamera(CameraMoveOf(c)); });
  }
  if (channel == "KEYFRAME") {
    return DecodeAndApply<keyframe_command_t>(data, [&](const auto& c) {
      TimelineEdit edit;
      const std::string problem = TimelineEditOf(c, &edit);
      return problem.empty() ? session->ApplyTimeline(edit) : problem;
    });
  }
  if (channel == "TIME") {
    return DecodeAndApply<time_command_t>(data, [&](const auto& c) {
      TimeControl control;
      const std::string problem = TimeControlOf(c, &control);
      return problem.empty() ? session->ApplyTime(control) : problem;
    });
  }
  if (channel == "MODEL") {
    return DecodeAndApply<model_t>(data, [&](const auto& c) {
      ModelSwitch model;
      const std::string problem = ModelSwitchOf(c, &model);
      return problem.empty() ? session->ApplyModel(model) : problem;
    });
  }
  if (channel == "DESIGN") {
    return DecodeAndApply<design_piece_t>(data, [&](const auto& c) {
      const DesignFilePtr file = designs != nullptr ? designs->Find(c.digest) : nullptr;
      if (!file)
        return "DESIGN: the image " + PrintableText(c.name, 128) + " (SHA-256 " +
               PrintableText(c.digest, 64) +
               ") is not at hand: a recording holds it on DESIGN_FILE before the command";
      return session->ApplyDesign(file);
    });
  }
  if (channel == "REFRESH") return DecodeAndApply<refresh_request_t>(data, [](const auto&) { return ""; });
  return "channel " + channel +
         ": not a command channel; allowed WIND, PARAM, CAMERA, KEYFRAME, TIME, DESIGN, MODEL, REFRESH";
}

}  // namespace flagsim
