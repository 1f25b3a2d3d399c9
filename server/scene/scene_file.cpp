#include "server/scene/scene_file.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string_view>
#include <utility>

#include "server/render/camera_moves.hpp"
#include "server/scene/parameter_table.hpp"
#include "server/scene/scene_timeline.hpp"

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
    if (name == "width") scene->service.width_follows_design = false;  // the scene sets it
    if (name == "design")
      throw SceneError(Where(source, node) + "design goes at the top level: design = \"NAME\" or \"PATH\"");
    const std::string text = ValueText(node);
    const std::string problem = text.empty() ? name + ": not a number, switch or name"
                                             : ParameterTable::Get().Assign(name, text, scene);
    if (!problem.empty()) throw SceneError(Where(source, node) + problem);
  }
}

/// design = "NAME" (a built-in design) or "PATH" (an image file, relative to the scene file's
/// folder).
void ReadDesign(const toml::node& node, const std::string& source, Scene* scene) {
  const auto value = node.value<std::string>();
  if (!value || value->empty())
    throw SceneError(Where(source, node) +
                     "design must be a string: a built-in design's name or an image's path");
  const std::vector<std::string>& names = render::FlagDesignNames();
  const bool built_in = std::find(names.begin(), names.end(), *value) != names.end();
  if (built_in && *value != "image") {
    const std::string problem = ParameterTable::Get().Assign("design", *value, scene);
    if (!problem.empty()) throw SceneError(Where(source, node) + problem);
    return;
  }
  std::filesystem::path path(*value);
  if (path.is_relative()) path = std::filesystem::path(source).parent_path() / path;
  const std::string problem = LoadDesignFile(path.string(), &scene->service.design_file);
  if (!problem.empty()) {
    std::string known;
    for (size_t i = 0; i + 1 < names.size(); ++i) known += (known.empty() ? "" : ", ") + names[i];
    throw SceneError(Where(source, node) + "design: '" + *value + "' is neither a built-in design (" + known +
                     ") nor an image file: " + problem);
  }
  scene->service.design = render::FlagDesign::kImage;
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
  // Checked as a WIND command is, once the table is read; the error names the line of the key
  // its field is ("velocity.x: ..." => wind.velocity's), as the other errors of a file do.
  const std::string problem = ParameterTable::CheckWind(scene->wind);
  if (problem.empty()) return;
  const toml::node* key = table.get(problem.substr(0, problem.find_first_of(".:")));
  throw SceneError(Where(source, key != nullptr ? *key : table) + "wind." + problem);
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

sim::Vec3 Triple(const toml::node& node, const std::string& what, const std::string& unit,
                 const std::string& source) {
  const toml::array* array = node.as_array();
  if (array == nullptr || array->size() != 3)
    throw SceneError(Where(source, node) + what + " must be [x, y, z] in " + unit);
  sim::Vec3 triple;
  for (int k = 0; k < 3; ++k) triple[k] = Number(*array->get(k), what, source);
  return triple;
}

bool Switch(const toml::node& node, const std::string& what, const std::string& source) {
  if (const auto* value = node.as_boolean()) return value->get();
  throw SceneError(Where(source, node) + what + " must be true or false");
}

sim::ControlLaw Law(const toml::node& node, const std::string& what, const std::string& source) {
  const auto& names = sim::ControlLawNames();
  const auto name = node.value<std::string>();
  const auto found = name ? std::find(names.begin(), names.end(), *name) : names.end();
  if (found == names.end()) {
    throw SceneError(Where(source, node) + what + " must be one of: step, linear, smooth, cubic");
  }
  return static_cast<sim::ControlLaw>(found - names.begin());
}

/// camera = { eye = [x, y, z], target = [x, y, z], fov = degrees }, all three.
sim::CameraControl KeyCamera(const toml::table& table, const std::string& what, const std::string& source) {
  for (const char* needed : {"eye", "target", "fov"}) {
    if (!table.contains(needed)) {
      throw SceneError(Where(source, table) + what + " needs eye, target and fov; " + needed + " is missing");
    }
  }
  sim::CameraControl camera;
  for (const auto& [key, node] : table) {
    const std::string name(key.str());
    if (name == "eye") {
      camera.eye = Triple(node, what + ".eye", "m", source);
    } else if (name == "target") {
      camera.target = Triple(node, what + ".target", "m", source);
    } else if (name == "fov") {
      camera.fov = Number(node, what + ".fov", source);
    } else {
      throw SceneError(Where(source, node) + "unknown key " + what + "." + name +
                       "; known: eye, target, fov");
    }
  }
  return camera;
}

/// One [[timeline.keys]] table: time, law, wind, gust, parameters, camera.
sim::Keyframe ReadKey(const toml::table& table, const std::string& what, const std::string& source) {
  sim::Keyframe key;
  bool has_time = false;
  const toml::node* gust = nullptr;
  for (const auto& [name_view, node] : table) {
    const std::string name(name_view.str());
    if (name == "time") {
      key.time = Number(node, what + ".time", source);
      has_time = true;
    } else if (name == "law") {
      key.law = Law(node, what + ".law", source);
    } else if (name == "wind") {
      key.wind = sim::WindControl{Triple(node, what + ".wind", "m/s", source), 0};
    } else if (name == "gust") {
      gust = &node;
    } else if (name == "parameters") {
      for (const auto& [parameter_view, value] : Table(node, what + ".parameters", source)) {
        const std::string parameter(parameter_view.str());
        key.parameters.push_back({parameter, Number(value, what + ".parameters." + parameter, source)});
      }
    } else if (name == "camera") {
      key.camera = KeyCamera(Table(node, what + ".camera", source), what + ".camera", source);
    } else {
      throw SceneError(Where(source, node) + "unknown key " + what + "." + name +
                       "; known: time, law, wind, gust, parameters, camera");
    }
  }
  if (!has_time) throw SceneError(Where(source, table) + what + ".time is missing (s)");
  if (gust != nullptr) {
    if (!key.wind)
      throw SceneError(Where(source, *gust) + what + ".gust needs wind = [vx, vy, vz] in the key");
    key.wind->gust = Number(*gust, what + ".gust", source);
  }
  const std::string problem = CheckKeyframe(key, what);
  if (!problem.empty()) throw SceneError(Where(source, table) + problem);
  return key;
}

void ReadTimeline(const toml::table& table, const std::string& source, Scene* scene) {
  sim::Timeline& timeline = scene->timeline;
  for (const auto& [key, node] : table) {
    const std::string name(key.str());
    if (name == "play") {
      if (Switch(node, "timeline.play", source)) timeline.Play();
    } else if (name == "loop") {
      timeline.SetLoop(Switch(node, "timeline.loop", source));
    } else if (name == "speed") {
      timeline.SetSpeed(Number(node, "timeline.speed", source));
    } else if (name == "keys") {
      const toml::array* keys = node.as_array();
      if (keys == nullptr || !keys->is_array_of_tables()) {
        throw SceneError(Where(source, node) + "timeline.keys must be tables, [[timeline.keys]]");
      }
      if (keys->size() > TimelineLimits::kMaxKeys) {
        throw SceneError(Where(source, node) + "timeline.keys: " + std::to_string(keys->size()) +
                         " of them; allowed at most " + std::to_string(TimelineLimits::kMaxKeys));
      }
      for (size_t i = 0; i < keys->size(); ++i) {
        const std::string what = "timeline.keys[" + std::to_string(i) + "]";
        const sim::Keyframe frame = ReadKey(*keys->get(i)->as_table(), what, source);
        if (timeline.Find(frame.time) != nullptr) {
          throw SceneError(Where(source, *keys->get(i)) + what + ".time: " +
                           ValueText(*keys->get(i)->as_table()->get("time")) + " s already has a key");
        }
        timeline.Add(frame);
      }
    } else {
      throw SceneError(Where(source, node) + "unknown key timeline." + name +
                       "; known: play, loop, speed, keys");
    }
  }
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
    } else if (name == "settle") {
      const auto value = node.value<double>();
      if (!value || !(*value >= 0 && *value <= Scene::kMaxSettle)) {
        throw SceneError(Where(source, node) + "settle must be a number of seconds, 0 .. " +
                         std::to_string(int(Scene::kMaxSettle)));
      }
      scene.settle = *value;
    } else if (name == "design") {
      ReadDesign(node, source, &scene);
    } else if (name == "parameters") {
      ReadParameters(Table(node, name, source), source, &scene);
    } else if (name == "wind") {
      ReadWind(Table(node, name, source), source, &scene);
    } else if (name == "camera") {
      ReadCamera(Table(node, name, source), source, &scene);
    } else if (name == "timeline") {
      ReadTimeline(Table(node, name, source), source, &scene);
    } else {
      throw SceneError(
          Where(source, node) + "unknown key '" + name +
          "'; known: name, description, seed, settle, design, [parameters], [wind], [camera], [timeline]");
    }
  }
  const DesignFilePtr& image = scene.service.design_file;
  if (image && scene.service.width_follows_design) scene.sim.width = image->WidthFor(scene.sim.height);
  ParameterTable::SettleAutoModel(&scene);
  std::string problem = ParameterTable::CheckConsistency(scene);
  if (!problem.empty()) throw SceneError(source + ": " + problem);
  problem = CheckTimeline(scene.timeline, scene);
  if (!problem.empty()) throw SceneError(source + ": timeline." + problem);
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
  std::string presets;
  for (const std::string& name : PresetNames()) presets += (presets.empty() ? "" : ", ") + name;
  std::error_code ignored;
  if (std::filesystem::is_directory(preset_or_path, ignored)) {
    throw SceneError("'" + preset_or_path +
                     "' is a directory; give a scene file (.toml) or a preset: " + presets);
  }
  std::ifstream file(preset_or_path);
  if (!file) {
    throw SceneError("no scene file '" + preset_or_path +
                     "' and no preset of that name; presets: " + presets);
  }
  std::ostringstream text;
  text << file.rdbuf();
  return ParseScene(text.str(), preset_or_path);
}

}  // namespace flagsim
