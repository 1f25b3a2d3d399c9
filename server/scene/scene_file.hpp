// Scene files: TOML, human-written. Every key is optional and overrides the defaults of Scene;
// parameters are checked by the parameter table exactly as PARAM commands are.
//
//   name = "gale"                      description = "..."            seed = 3
//   [parameters]   any name of the parameter table, e.g.  stiffness = 4000
//   [wind]         velocity = [vx, vy, vz] (m/s)   gust = 0.4   ramp_time = 0 (s)
//   [camera]       eye = [x, y, z]   target = [x, y, z] (m)   fov = 40 (degrees)   width, height (px)
//   [timeline]     play = false   loop = false   speed = 1 (timeline s per simulated s)
//   [[timeline.keys]]   time = 0 (s)   law = "linear" (step, linear, smooth, cubic)
//                  wind = [vx, vy, vz] (m/s)   gust = 0 (needs wind)
//                  parameters = { stiffness = 1500 }   (animatable parameters only)
//                  camera = { eye = [x, y, z], target = [x, y, z], fov = 40 }  (all three)
//                  a key sets any of wind, parameters and camera; see scene_timeline.hpp
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "server/scene/scene.hpp"

namespace flagsim {

/// A scene file that cannot be read, or says something not allowed.
class SceneError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Parses TOML text; `source` names it in errors. Throws SceneError.
Scene ParseScene(const std::string& text, const std::string& source);

/// A preset name ("breeze", "calm", "gale", "hanging") or a path to a .toml file.
Scene LoadScene(const std::string& preset_or_path);

/// The presets built into the binary, by name.
std::vector<std::string> PresetNames();
std::string PresetText(const std::string& name);  ///< "" if there is no such preset

}  // namespace flagsim
