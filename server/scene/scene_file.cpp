#include "scene_file.hpp"

#include <toml++/toml.h>

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string_view>
#include <utility>

#include "parameter_table.hpp"
#include "render/camera_moves.hpp"

namespace flagsim {

/// (stem, text) of each scenes/*.toml, generated at build time.
const std::vector<std::pair<std::string_view, std::string_view>>& ScenePresets();

namespace {

std::string Where(const std::string& source, const toml::node& node) {
  return source + ":" + std::to_string(node.source().begin.line) + ": ";
}

/// A TOML value as the parameter table's text: 1500, 0.25, true, "seed" -> seed.
std::string ValueText(const toml::node& node) {
  if (const auto* text = node.as_string()) return text->get();
  if (const auto* flag = node.as_boolean()) return flag->get() ? "true" : "false";
  if (const auto* integer = node.as_integer()) return std::to_string(integer->get());
  if (const auto* real = node.as_floating_point()) {
    char buffer[64];
    const auto result = std::to_chars(buffer, buffer + sizeof(buffer), real->get());
    return std::string(buffer, result.ptr);
  }
  return "";  // arrays, tables and dates are no parameter's value
}

double Number(const toml::node& node, const std::string& what, const std::string& source) {
  if (const auto value = node.value<double>()) return *value;
  throw SceneError(Where(source, node) + what + " must be a number");
}

void ReadParameters(const toml::table& table, const std::string& source, Scene* scene) {
  for (const auto& [key, node] : table) {
    const std::string name(key.str());
    const std::string text = ValueText(node);
    const std::string problem = text.empty() ? name + ": not a number, switch or name"
                                             : ParameterTable::Get().Assign(name, text, scene);
    if (!problem.empty()) throw SceneError(Where(source, node) + problem);
  }
}

void ReadWind(const toml::table& table, const std::string& source, Scene* scene) {
  for (const auto& [key, node] : table) {
    const std::string name(key.str());
    if (name == "velocity") {
      const toml::array* array = node.as_array();
      if (array == nullptr || array->size() != 3) {
        throw SceneError(Where(source, node) + "wind.velocity must be [vx, vy, vz] in m/s");
      }
      for (int k = 0; k < 3; ++k) scene->wind.velocity[k] = Number(*array->get(k), "wind.velocity", source);
    } else if (name == "gust") {
      scene->wind.gust = Number(node, "wind.gust", source);
    } else if (name == "ramp_time") {
      scene->wind.ramp_time = Number(node, "wind.ramp_time", source);
    } else {
      throw SceneError(Where(source, node) + "unknown key wind." + name +
                       "; known: velocity, gust, ramp_time");
    }
  }
}

Eigen::Vector3d Vector(const toml::node& node, const std::string& what, const std::string& source) {
  const toml::array* array = node.as_array();
  if (array == nullptr || array->size() != 3)
    throw SceneError(Where(source, node) + what + " must be [x, y, z] in m");
  Eigen::Vector3d vector;
  for (int k = 0; k < 3; ++k) vector[k] = Number(*array->get(k), what, source);
  if (!vector.allFinite() || vector.norm() > render::CameraMove::kMaxDistance) {
    throw SceneError(Where(source, node) + what + " must be finite, within 1000 m of the origin");
  }
  return vector;
}

int Pixels(const toml::node& node, const std::string& what, int most, const std::string& source) {
  const auto value = node.value<int64_t>();
  if (!value || *value < render::CameraMove::kMinSize || *value > most) {
    throw SceneError(Where(source, node) + what + " must be an integer, 16 .. " + std::to_string(most) +
                     " px");
  }
  return static_cast<int>(*value);
}

void ReadCamera(const toml::table& table, const std::string& source, Scene* scene) {
  render::Camera& camera = scene->camera;
  for (const auto& [key, node] : table) {
    const std::string name(key.str());
    if (name == "eye") {
      camera.eye = Vector(node, "camera.eye", source);
    } else if (name == "target") {
      camera.target = Vector(node, "camera.target", source);
    } else if (name == "fov") {
      const double degrees = Number(node, "camera.fov", source);
      if (!(degrees >= 10 && degrees <= 120))
        throw SceneError(Where(source, node) + "camera.fov: allowed 10 .. 120 degrees");
      camera.fov_y = degrees * M_PI / 180;
    } else if (name == "width") {
      camera.width = Pixels(node, "camera.width", render::CameraMove::kMaxWidth, source);
    } else if (name == "height") {
      camera.height = Pixels(node, "camera.height", render::CameraMove::kMaxHeight, source);
    } else {
      throw SceneError(Where(source, node) + "unknown key camera." + name +
                       "; known: eye, target, fov, width, height");
    }
  }
  if ((camera.target - camera.eye).norm() < 1e-3)
    throw SceneError(source + ": camera.eye and camera.target coincide");
}

const toml::table& Table(const toml::node& node, const std::string& what, const std::string& source) {
  if (const toml::table* table = node.as_table()) return *table;
  throw SceneError(Where(source, node) + what + " must be a table, [" + what + "]");
}

}  // namespace

Scene ParseScene(const std::string& text, const std::string& source) {
  toml::table root;
  try {
    root = toml::parse(text, source);
  } catch (const toml::parse_error& error) {
    throw SceneError(source + ":" + std::to_string(error.source().begin.line) + ": " +
                     std::string(error.description()));
  }
  Scene scene;
  for (const auto& [key, node] : root) {
    const std::string name(key.str());
    if (name == "name" || name == "description") {
      const auto value = node.value<std::string>();
      if (!value) throw SceneError(Where(source, node) + name + " must be a string");
      (name == "name" ? scene.name : scene.description) = *value;
    } else if (name == "seed") {
      const auto value = node.value<int64_t>();
      if (!value || *value < 0) throw SceneError(Where(source, node) + "seed must be an integer >= 0");
      scene.seed = static_cast<uint64_t>(*value);
    } else if (name == "parameters") {
      ReadParameters(Table(node, name, source), source, &scene);
    } else if (name == "wind") {
      ReadWind(Table(node, name, source), source, &scene);
    } else if (name == "camera") {
      ReadCamera(Table(node, name, source), source, &scene);
    } else {
      throw SceneError(Where(source, node) + "unknown key '" + name +
                       "'; known: name, description, seed, [parameters], [wind], [camera]");
    }
  }
  for (const std::string& problem :
       {ParameterTable::CheckConsistency(scene), ParameterTable::CheckWind(scene.wind)}) {
    if (!problem.empty()) throw SceneError(source + ": " + problem);
  }
  return scene;
}

std::vector<std::string> PresetNames() {
  std::vector<std::string> names;
  for (const auto& [name, text] : ScenePresets()) names.emplace_back(name);
  return names;
}

std::string PresetText(const std::string& name) {
  for (const auto& [preset, text] : ScenePresets()) {
    if (preset == name) return std::string(text);
  }
  return "";
}

Scene LoadScene(const std::string& preset_or_path) {
  const std::string preset = PresetText(preset_or_path);
  if (!preset.empty()) return ParseScene(preset, preset_or_path);
  std::ifstream file(preset_or_path);
  if (!file) {
    std::string presets;
    for (const std::string& name : PresetNames()) presets += (presets.empty() ? "" : ", ") + name;
    throw SceneError("no scene file '" + preset_or_path +
                     "' and no preset of that name; presets: " + presets);
  }
  std::ostringstream text;
  text << file.rdbuf();
  return ParseScene(text.str(), preset_or_path);
}

}  // namespace flagsim
