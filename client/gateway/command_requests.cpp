#include "client/gateway/command_requests.hpp"

#include <cmath>
#include <cstdio>

#include "client/gateway/bus_json.hpp"

namespace flagsim::gateway {
namespace {

using nlohmann::json;

constexpr double kRadiansPerDegree = M_PI / 180;

/// Reads an optional number field into *value (kept when absent); "" or the reason.
std::string ReadNumber(const json& object, const char* field, double* value, const std::string& where = "") {
  const auto found = object.find(field);
  if (found == object.end()) return "";
  if (!found->is_number()) return where + field + ": must be a number";
  *value = found->get<double>();
  return "";
}

template <class Flag>  // bool, or LCM's boolean (int8_t)
std::string ReadBool(const json& object, const char* field, Flag* value, const std::string& where = "") {
  const auto found = object.find(field);
  if (found == object.end()) return "";
  if (!found->is_boolean()) return where + field + ": must be true or false";
  *value = found->get<bool>();
  return "";
}

/// An [x, y, z] of numbers; `required` refuses its absence.
std::string ReadVector(const json& object, const char* field, double* vector, bool required,
                       const std::string& where = "") {
  const auto found = object.find(field);
  if (found == object.end()) return required ? where + field + ": required, [x, y, z] in m" : "";
  if (!found->is_array() || found->size() != 3) return where + field + ": must be [x, y, z], three numbers";
  for (int k = 0; k < 3; ++k) {
    if (!(*found)[k].is_number()) return where + field + ": must be [x, y, z], three numbers";
    vector[k] = (*found)[k].get<double>();
  }
  return "";
}

// "pixel": [x, y] in px (x right, y down from the top left), into vector's x and y.
std::string ReadPixel(const json& object, double* vector) {
  const auto found = object.find("pixel");
  if (found == object.end()) return "pixel: required, [x, y] in px from the picture's top left";
  if (!found->is_array() || found->size() != 2 || !(*found)[0].is_number() || !(*found)[1].is_number()) {
    return "pixel: must be [x, y], two numbers in px";
  }
  vector[0] = (*found)[0].get<double>();
  vector[1] = (*found)[1].get<double>();
  vector[2] = 0;
  return "";
}

std::string RequireObject(const json& request) {
  return request.is_object() ? "" : "the request must be a JSON object";
}

std::string Operation(const json& request, std::string* operation) {
  const auto found = request.find("operation");
  if (found == request.end() || !found->is_string()) return "operation: required, a string";
  *operation = found->get<std::string>();
  return "";
}

/// Runs the readers in order and returns the first complaint.
template <class... Problems>
std::string First(Problems... problems) {
  std::string first;
  ((first = first.empty() ? problems : first), ...);
  return first;
}

std::string Formatted(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.17g", value);
  return text;
}

// The camera operations by name: their code and what they read.
struct CameraOperation {
  const char* name;
  int8_t code;
};
constexpr CameraOperation kCameraOperations[] = {
    {"rotate_x", camera_command_t::ROTATE_X}, {"rotate_y", camera_command_t::ROTATE_Y},
    {"rotate_z", camera_command_t::ROTATE_Z}, {"translate", camera_command_t::TRANSLATE},
    {"scale", camera_command_t::SCALE},       {"orbit", camera_command_t::ORBIT},
    {"look_at", camera_command_t::LOOK_AT},   {"size", camera_command_t::SET_IMAGE_SIZE},
    {"reset", camera_command_t::RESET},       {"zoom", camera_command_t::ZOOM},
    {"eye", camera_command_t::SET_EYE},       {"fov", camera_command_t::SET_FOV},
    {"frame", camera_command_t::FRAME},       {"zoom_at", camera_command_t::ZOOM_AT},
};

std::string CameraNames() {
  std::string names;
  for (const CameraOperation& operation : kCameraOperations)
    names += (names.empty() ? "" : ", ") + std::string(operation.name);
  return names;
}

std::string ReadInteger(const json& object, const char* field, int32_t* value) {
  const auto found = object.find(field);
  if (found == object.end()) return "";
  if (!found->is_number_integer()) return std::string(field) + ": must be an integer";
  *value = static_cast<int32_t>(std::clamp<int64_t>(found->get<int64_t>(), INT32_MIN, INT32_MAX));
  return "";
}

// The key of an ADD or CHANGE: time, law, and any of wind, parameters, camera.
std::string KeyOf(const json& key, timeline_key_t* out) {
  if (!key.is_object()) return "key: required for add and change, an object";
  out->law = timeline_key_t::LAW_LINEAR;
  std::string problem = ReadNumber(key, "time", &out->time, "key.");
  if (!problem.empty()) return problem;
  if (const auto law = key.find("law"); law != key.end()) {
    out->law = static_cast<int8_t>(law->is_string() ? LawOfName(law->get<std::string>()) : -1);
    if (out->law < 0) return "key.law: must be one of step, linear, smooth, cubic";
  }
  if (const auto wind = key.find("wind"); wind != key.end()) {
    if (!wind->is_object()) return "key.wind: must be {velocity: [x, y, z], gust}";
    out->has_wind = true;
    problem = First(ReadVector(*wind, "velocity", out->wind_velocity, true, "key.wind."),
                    ReadNumber(*wind, "gust", &out->wind_gust, "key.wind."));
    if (!problem.empty()) return problem;
  }
  if (const auto parameters = key.find("parameters"); parameters != key.end()) {
    if (!parameters->is_object()) return "key.parameters: must be {NAME: number, ...}";
    for (const auto& [name, value] : parameters->items()) {
      if (!value.is_number()) return "key.parameters." + name + ": must be a number";
      out->names.push_back(name);
      out->values.push_back(value.get<double>());
    }
    out->num_parameters = static_cast<int32_t>(out->names.size());
  }
  if (const auto camera = key.find("camera"); camera != key.end()) {
    if (!camera->is_object()) return "key.camera: must be {eye, target, fov}";
    out->has_camera = true;
    out->camera_fov = 40;
    return First(ReadVector(*camera, "eye", out->camera_eye, true, "key.camera."),
                 ReadVector(*camera, "target", out->camera_target, true, "key.camera."),
                 ReadNumber(*camera, "fov", &out->camera_fov, "key.camera."));
  }
  return "";
}

}  // namespace

std::string WindCommandOf(const json& request, wind_command_t* command) {
  return First(RequireObject(request), ReadVector(request, "velocity", command->velocity, true),
               ReadNumber(request, "gust", &command->gust), ReadNumber(request, "ramp", &command->ramp_time));
}

std::string ParameterText(const std::string& name, const json& value, std::string* error) {
  if (value.is_boolean()) return value.get<bool>() ? "true" : "false";
  if (value.is_number_integer()) return std::to_string(value.get<int64_t>());
  if (value.is_number()) return Formatted(value.get<double>());
  if (value.is_string()) return value.get<std::string>();
  *error =
      name + ": a value must be a number, true or false, or a name; got " + std::string(value.type_name());
  return "";
}

std::string SetCommandOf(const json& request, param_command_t* command) {
  std::string problem = First(RequireObject(request), ReadBool(request, "reset", &command->reset_to_scene));
  if (!problem.empty()) return problem;
  if (const auto parameters = request.find("parameters"); parameters != request.end()) {
    if (!parameters->is_object()) return "parameters: must be {NAME: value, ...}";
    for (const auto& [name, value] : parameters->items()) {
      const std::string text = ParameterText(name, value, &problem);
      if (!problem.empty()) return "parameters." + problem;
      command->names.push_back(name);
      command->values.push_back(text);
    }
  }
  command->num_assignments = static_cast<int32_t>(command->names.size());
  if (command->num_assignments == 0 && !command->reset_to_scene) return "parameters: nothing to set";
  return "";
}

std::string CameraCommandOf(const json& request, camera_command_t* command) {
  std::string name;
  std::string problem = First(RequireObject(request), Operation(request, &name));
  if (!problem.empty()) return problem;
  command->operation = 0;
  for (const CameraOperation& operation : kCameraOperations) {
    if (name == operation.name) command->operation = operation.code;
  }
  if (command->operation == 0) return "operation: '" + name + "' is not one; allowed " + CameraNames();
  double degrees = 0, degrees2 = 0;
  command->factor = 1;
  const bool needs_vector = name == "translate" || name == "look_at" || name == "eye";
  problem =
      First(ReadNumber(request, "degrees", &degrees), ReadNumber(request, "degrees2", &degrees2),
            name == "zoom_at" ? ReadPixel(request, command->vector)
                              : ReadVector(request, "vector", command->vector, needs_vector),
            ReadNumber(request, "factor", &command->factor), ReadInteger(request, "width", &command->width),
            ReadInteger(request, "height", &command->height));
  command->angle = degrees * kRadiansPerDegree;
  command->angle2 = degrees2 * kRadiansPerDegree;
  return problem;
}

std::string KeyframeCommandOf(const json& request, keyframe_command_t* command) {
  static const std::pair<const char*, int8_t> kOperations[] = {
      {"add", keyframe_command_t::ADD},       {"change", keyframe_command_t::CHANGE},
      {"remove", keyframe_command_t::REMOVE}, {"clear", keyframe_command_t::CLEAR},
      {"play", keyframe_command_t::PLAY},     {"pause", keyframe_command_t::PAUSE},
      {"seek", keyframe_command_t::SEEK},     {"loop", keyframe_command_t::LOOP},
      {"speed", keyframe_command_t::SPEED}};
  std::string name;
  std::string problem = First(RequireObject(request), Operation(request, &name));
  if (!problem.empty()) return problem;
  command->operation = 0;
  for (const auto& [operation, code] : kOperations) {
    if (name == operation) command->operation = code;
  }
  if (command->operation == 0) {
    return "operation: '" + name +
           "' is not one; allowed add, change, remove, clear, play, pause, seek, loop, speed";
  }
  command->speed = 1;
  problem =
      First(ReadNumber(request, "time", &command->time), ReadNumber(request, "speed", &command->speed),
            ReadBool(request, "loop", &command->loop), ReadBool(request, "keep_law", &command->keep_law));
  if (!problem.empty()) return problem;
  if (command->operation == keyframe_command_t::ADD || command->operation == keyframe_command_t::CHANGE) {
    const auto key = request.find("key");
    return KeyOf(key == request.end() ? json() : *key, &command->key);
  }
  return "";
}

std::string TimeCommandOf(const json& request, time_command_t* command) {
  std::string name;
  std::string problem = First(RequireObject(request), Operation(request, &name));
  if (!problem.empty()) return problem;
  if (name == "pause") {
    command->operation = time_command_t::PAUSE;
  } else if (name == "resume") {
    command->operation = time_command_t::RESUME;
  } else if (name == "step") {
    command->operation = time_command_t::STEP;
  } else {
    return "operation: '" + name + "' is not one; allowed pause, resume, step";
  }
  command->steps = 1;
  return ReadInteger(request, "steps", &command->steps);
}

}  // namespace flagsim::gateway
