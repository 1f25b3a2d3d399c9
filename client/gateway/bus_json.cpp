#include "client/gateway/bus_json.hpp"

#include <cinttypes>
#include <cmath>
#include <cstdio>

#include "flagsim/timeline_key_t.hpp"

namespace flagsim::gateway {
namespace {

using nlohmann::json;
// LCM's booleans are int8_t: each is turned into a JSON boolean with bool(...).

json Point(double x, double y, double z) { return {{"x", x}, {"y", y}, {"z", z}}; }

json Vector(const double* v) { return json::array({v[0], v[1], v[2]}); }

std::string Hex(int64_t hash) {
  char text[20];
  std::snprintf(text, sizeof(text), "%016" PRIx64, static_cast<uint64_t>(hash));
  return text;
}

const char* KindName(int8_t kind) {
  switch (kind) {
    case parameter_t::INTEGER:
      return "integer";
    case parameter_t::BOOLEAN:
      return "boolean";
    case parameter_t::CHOICE:
      return "choice";
    default:
      return "real";
  }
}

/// `value` as the protocol shows a parameter of `parameter`'s kind.
json ValueOfKind(const parameter_t& parameter, double value) {
  switch (parameter.kind) {
    case parameter_t::INTEGER:
      return static_cast<int64_t>(std::llround(value));
    case parameter_t::BOOLEAN:
      return value != 0;
    case parameter_t::CHOICE: {
      const auto index = static_cast<size_t>(std::llround(value));
      return index < parameter.choices.size() ? json(parameter.choices[index]) : json(value);
    }
    default:
      return value;
  }
}

json KeyJson(const timeline_key_t& key) {
  json out = {{"time", key.time}, {"law", LawName(key.law)}};
  if (key.has_wind) out["wind"] = {{"velocity", Vector(key.wind_velocity)}, {"gust", key.wind_gust}};
  json parameters = json::object();
  for (size_t i = 0; i < key.names.size() && i < key.values.size(); ++i)
    parameters[key.names[i]] = key.values[i];
  if (!parameters.empty()) out["parameters"] = parameters;
  if (key.has_camera) {
    out["camera"] = {
        {"eye", Vector(key.camera_eye)}, {"target", Vector(key.camera_target)}, {"fov", key.camera_fov}};
  }
  return out;
}

}  // namespace

json TimeJson(int64_t utime) {
  const int64_t micros = std::max<int64_t>(utime, 0);
  return {{"sec", micros / 1000000}, {"nsec", (micros % 1000000) * 1000}};
}

uint64_t Nanoseconds(int64_t utime) { return utime > 0 ? uint64_t(utime) * 1000 : 0; }

bool CameraMoved(const json& camera, json* last) {
  json pose = camera;
  pose.erase("frame_id");
  if (pose == *last) return false;
  *last = std::move(pose);
  return true;
}

std::string LawName(int law) {
  switch (law) {
    case timeline_key_t::LAW_STEP:
      return "step";
    case timeline_key_t::LAW_LINEAR:
      return "linear";
    case timeline_key_t::LAW_SMOOTH:
      return "smooth";
    case timeline_key_t::LAW_CUBIC:
      return "cubic";
    default:
      return "";
  }
}

int LawOfName(const std::string& name) {
  for (int law = timeline_key_t::LAW_STEP; law <= timeline_key_t::LAW_CUBIC; ++law) {
    if (LawName(law) == name) return law;
  }
  return -1;
}

json StatusJson(const status_t& s) {
  return {{"uptime", s.uptime},
          {"step", s.step},
          {"sim_time", s.sim_time},
          {"real_time_factor", s.real_time_factor},
          {"steps_per_second", s.steps_per_second},
          {"substeps", s.substeps},
          {"num_nodes", s.num_nodes},
          {"threads", s.threads},
          {"integrator", s.integrator},
          {"sleeping", bool(s.sleeping)},
          {"paused", bool(s.paused)},
          {"steps_owed", s.steps_owed},
          {"time_scale", s.time_scale},
          {"step_time_us", s.step_time_us},
          {"publish_time_us", s.publish_time_us},
          {"state_rate_hz", s.state_rate_hz},
          {"frame_rate_hz", s.frame_rate_hz},
          {"render_time_us", s.render_time_us},
          {"encode_time_us", s.encode_time_us},
          {"tiles_per_frame", s.tiles_per_frame},
          {"frame_bytes", s.frame_bytes},
          {"frames_skipped", s.frames_skipped},
          {"bytes_per_second", s.bytes_per_second},
          {"commands_accepted", s.commands_accepted},
          {"commands_rejected", s.commands_rejected},
          {"messages_dropped", s.messages_dropped},
          {"command_authentication", s.command_authentication},
          {"commands_unsigned", s.commands_unsigned},
          {"commands_unknown_key", s.commands_unknown_key},
          {"commands_bad_mac", s.commands_bad_mac},
          {"commands_replayed", s.commands_replayed},
          {"commands_stale", s.commands_stale},
          {"recoveries", s.recoveries},
          {"last_recovery", s.last_recovery},
          {"server_id", std::to_string(s.server_id)},  // a string: 63 bits do not fit a JavaScript number
          {"other_servers", s.other_servers},
          {"cols", s.cols},
          {"rows", s.rows},
          {"model_auto", s.model_auto},
          {"screen_error_px", s.screen_error_px},
          {"model_cost", s.model_cost},
          {"model_note", s.model_note}};
}

json ParameterValue(const parameter_t& parameter) { return ValueOfKind(parameter, parameter.value); }

json ParamsJson(const params_t& params) {
  json rows = json::array();
  for (const parameter_t& p : params.parameters) {
    rows.push_back({{"name", p.name},
                    {"unit", p.unit},
                    {"kind", KindName(p.kind)},
                    {"min", p.min_value},
                    {"max", p.max_value},
                    {"default", ValueOfKind(p, p.default_value)},
                    {"value", ParameterValue(p)},
                    {"value_text", p.value_text},
                    {"choices", p.choices},
                    {"description", p.description}});
  }
  return {{"parameters", rows}};
}

json ParameterValues(const params_t& params) {
  json values = json::array();
  for (const parameter_t& p : params.parameters)
    values.push_back({{"name", p.name}, {"value", ParameterValue(p)}});
  return values;
}

json TimelineJson(const timeline_t& t) {
  json keys = json::array();
  for (const timeline_key_t& key : t.keys) keys.push_back(KeyJson(key));
  return {{"step", t.step},
          {"playing", bool(t.playing)},
          {"position", t.position},
          {"speed", t.speed},
          {"loop", bool(t.loop)},
          {"last_key_time", t.last_key_time},
          {"gliding", bool(t.gliding)},
          {"keys", keys}};
}

// The tip is the fly end's top corner (row 0, last column), as flagctl watch prints it.
json StateSummaryJson(const state_t& s) {
  json out = {
      {"sim_time", s.sim_time},
      {"step", s.step},
      {"state_hash", Hex(s.state_hash)},
      {"cols", s.cols},
      {"rows", s.rows},
      {"kinetic_energy", s.kinetic_energy},
      {"wind", Point(s.wind[0], s.wind[1], s.wind[2])},
      {"wind_speed", std::sqrt(s.wind[0] * s.wind[0] + s.wind[1] * s.wind[1] + s.wind[2] * s.wind[2])},
      {"wind_gust", s.wind_gust},
      {"pole_top", Point(s.pole_top[0], s.pole_top[1], s.pole_top[2])}};
  const size_t tip = 3 * size_t(std::max<int64_t>(int64_t(s.cols) - 1, 0));
  if (s.cols > 0 && tip + 2 < s.position.size()) {
    const double x = s.position[tip], y = s.position[tip + 1], z = s.position[tip + 2];
    out["tip"] = Point(x, y, z);
    out["tip_from_pole"] = std::hypot(x - s.pole_top[0], z - s.pole_top[2]);
  }
  return out;
}

json CameraJson(const frame_t& f) {
  return {{"frame_id", f.frame_id},
          {"width", f.width},
          {"height", f.height},
          {"eye", Vector(f.camera_eye)},
          {"target", Vector(f.camera_target)},
          {"fov", f.camera_fov},
          {"view", std::vector<double>(f.view, f.view + 16)},
          {"projection", std::vector<double>(f.projection, f.projection + 16)}};
}

json AckJson(const ack_t& a) {
  return {{"client_id", a.client_id},     {"sequence", a.sequence}, {"channel", a.channel},
          {"accepted", bool(a.accepted)}, {"reason", a.reason},     {"step", a.step}};
}

std::string JsonText(const json& message) {
  return message.dump(-1, ' ', false, json::error_handler_t::replace);
}

}  // namespace flagsim::gateway
